#include "reference/cache_file.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/hash.h"

namespace sb::reference::detail {

using core::fnv1a64;
using core::ImageF;

namespace {

constexpr char kMagic[8] = {'S', 'B', 'R', 'E', 'F', '\r', '\n', '\x1a'};
// 2: the stop bounds, the penumbra and its source after the standard errors.
constexpr uint32_t kFileVersion = 2;

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool get(T& v) {
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get(std::string& s, uint32_t max_len) {
    uint32_t n = 0;
    if (!get(n) || n > max_len || bytes_.size() - pos_ < n) return false;
    s.assign(bytes_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool get(std::vector<uint8_t>& v, size_t n) {
    if (bytes_.size() - pos_ < n) return false;
    v.assign(bytes_.data() + pos_, bytes_.data() + pos_ + n);
    pos_ += n;
    return true;
  }
  bool get(std::vector<float>& v, size_t n) {
    if ((bytes_.size() - pos_) / sizeof(float) < n) return false;
    v.resize(n);
    std::memcpy(v.data(), bytes_.data() + pos_, n * sizeof(float));
    pos_ += n * sizeof(float);
    return true;
  }
  size_t pos() const { return pos_; }

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

}  // namespace

std::string encode_cache_file(const Result& r) {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kFileVersion);
  put(out, int32_t(r.visibility.width));
  put(out, int32_t(r.visibility.height));
  put(out, int32_t(r.spp));
  put(out, r.seed);
  put(out, uint32_t(r.method.size()));
  out += r.method;
  put(out, uint32_t(r.cache_key.size()));
  out += r.cache_key;
  out.append(reinterpret_cast<const char*>(r.visibility.data.data()),
             r.visibility.data.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(r.std_error.data.data()),
             r.std_error.data.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(r.stop_bound.data.data()),
             r.stop_bound.data.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(r.penumbra.data()), r.penumbra.size());
  put(out, uint32_t(r.penumbra_source.size()));
  out += r.penumbra_source;
  if (r.method == kAdaptiveMethod)  // uniform files stay as they were
    out.append(reinterpret_cast<const char*>(r.samples.data.data()),
               r.samples.data.size() * sizeof(float));
  put(out, fnv1a64(out));
  return out;
}

bool decode_cache_file(const std::string& bytes, const CacheFileExpectation& expected, Result& r) {
  if (bytes.size() < sizeof(kMagic) + sizeof(uint64_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    return false;
  uint64_t stored_sum = 0;
  std::memcpy(&stored_sum, bytes.data() + bytes.size() - sizeof(stored_sum), sizeof(stored_sum));
  if (stored_sum != fnv1a64(std::string_view(bytes.data(), bytes.size() - sizeof(stored_sum))))
    return false;
  Reader in(bytes);
  char magic[sizeof(kMagic)];
  uint32_t version = 0;
  int32_t w = 0, h = 0, spp = 0;
  uint64_t seed = 0;
  std::string method, stored_key;
  if (!in.get(magic) || !in.get(version) || version != kFileVersion || !in.get(w) || !in.get(h) ||
      !in.get(spp) || !in.get(seed) || !in.get(method, 256) || !in.get(stored_key, 256))
    return false;
  if (w != expected.width || h != expected.height || spp != expected.spp || seed != expected.seed ||
      method != expected.method || stored_key != expected.key)
    return false;
  const size_t n = size_t(w) * size_t(h);
  ImageF vis(w, h, 1), se(w, h, 1), bound(w, h, 1), samples;
  std::vector<uint8_t> penumbra;
  std::string penumbra_source;
  if (!in.get(vis.data, n) || !in.get(se.data, n) || !in.get(bound.data, n) ||
      !in.get(penumbra, n) || !in.get(penumbra_source, 16))
    return false;
  if (penumbra_source != kPenumbraExact && penumbra_source != kPenumbraSampled) return false;
  if (expected.max_samples) {
    samples = ImageF(w, h, 1);
    if (!in.get(samples.data, n)) return false;
    for (float v : samples.data)
      if (!(v >= 0.0f && v <= *expected.max_samples)) return false;
  }
  if (in.pos() + sizeof(uint64_t) != bytes.size()) return false;
  for (size_t i = 0; i < n; ++i)
    if (!(vis.data[i] >= 0.0f && vis.data[i] <= 1.0f && se.data[i] >= 0.0f && se.data[i] <= 1.0f &&
          bound.data[i] >= 0.0f && bound.data[i] <= 1.0f && penumbra[i] <= 1))
      return false;
  r.visibility = std::move(vis);
  r.std_error = std::move(se);
  r.stop_bound = std::move(bound);
  r.penumbra = std::move(penumbra);
  r.penumbra_source = std::move(penumbra_source);
  if (expected.max_samples) r.samples = std::move(samples);
  return true;
}

bool read_cache_file(const std::filesystem::path& path, std::string& bytes) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::ostringstream ss;
  ss << f.rdbuf();
  if (f.bad()) return false;
  bytes = std::move(ss).str();
  return true;
}

}  // namespace sb::reference::detail
