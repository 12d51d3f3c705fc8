#include "config/resolutions.h"

#include <cstdint>
#include <stdexcept>

namespace sb::config {

using core::describe;

namespace {

constexpr uint64_t kMaxPixels = uint64_t(1) << 24;

}  // namespace

using json = nlohmann::json;

Resolution parse_resolution(const ConfigReader& r, const json& v, const std::string& p) {
  Resolution res;
  if (v.is_array() && v.size() == 2) {
    res.width = r.integer(v[0], p + "/0", 1, 16384);
    res.height = r.integer(v[1], p + "/1", 1, 16384);
  } else if (v.is_string()) {
    const std::string s = v.get<std::string>();
    const auto x = s.find('x');
    try {
      size_t used = 0;
      res.width = std::stoi(s.substr(0, x), &used);
      if (x == std::string::npos || used != x) throw std::invalid_argument(s);
      res.height = std::stoi(s.substr(x + 1), &used);
      if (used != s.size() - x - 1) throw std::invalid_argument(s);
    } catch (const std::exception&) {
      r.fail(p, "expected \"WIDTHxHEIGHT\" or [width, height], found " + v.dump());
    }
    if (res.width < 1 || res.height < 1 || res.width > 16384 || res.height > 16384)
      r.fail(p, "expected sizes in [1, 16384], found " + v.dump());
  } else {
    r.fail(p, "expected \"WIDTHxHEIGHT\" or [width, height], found " + describe(v));
  }
  // Every pixel costs the G-buffer, the reference and the images about 100 bytes.
  if (uint64_t(res.width) * uint64_t(res.height) > kMaxPixels)
    r.fail(p, "expected at most " + std::to_string(kMaxPixels) + " pixels (4096x4096), found " +
                  res.label());
  return res;
}

}  // namespace sb::config
