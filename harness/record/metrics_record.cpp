#include "record/metrics_record.h"

#include <limits>
#include <type_traits>
#include <vector>

#include "record/record_json.h"

namespace sb::record {

using json = nlohmann::json;

namespace {

// A number of RegionStats by its record key: the description's members
// that are numbers.
class NumberOf {
 public:
  NumberOf(const RegionStats& s, const std::string& key) : s_(s), key_(key) {}
  std::optional<double> value;

  template <class M>
  void field(const char* key, M RegionStats::*member, const FieldInfo& /*info*/ = {}) {
    if constexpr (std::is_arithmetic_v<M>) {
      if (key_ == key) value = static_cast<double>(s_.*member);
    } else if constexpr (std::is_same_v<M, std::optional<double>>) {
      if (key_ == key) value = (s_.*member).value_or(std::numeric_limits<double>::quiet_NaN());
    }
  }
  template <class W, class R>
  void custom(const char*, const char*, const FieldInfo&, W&&, R&&) {}

 private:
  const RegionStats& s_;
  const std::string& key_;
};

std::optional<double> number_of(const RegionStats& s, const std::string& key) {
  NumberOf n(s, key);
  RegionStats::describe(n);
  return n.value;
}

}  // namespace

void RegionStats::read_max_pixel(RegionStats& s, const Fields& f) {
  const std::vector<int> max_pixel = f.get<std::vector<int>>("max_pixel");
  if (max_pixel.size() != 2) f.fail("max_pixel", "expected [x, y]");
  s.max_x = max_pixel[0];
  s.max_y = max_pixel[1];
}

json RegionStats::to_json() const { return write_record(*this); }
RegionStats RegionStats::from_json(const Fields& f) { return read_record<RegionStats>(f); }
json ImageMetrics::to_json() const { return write_record(*this); }
ImageMetrics ImageMetrics::from_json(const Fields& f) { return read_record<ImageMetrics>(f); }
json MetricsRecord::to_json() const { return write_record(*this); }
MetricsRecord MetricsRecord::from_json(const Fields& f) { return read_record<MetricsRecord>(f); }

std::optional<MetricPath> MetricPath::parse(const std::string& dotted) {
  const size_t first = dotted.find('.');
  if (first == std::string::npos) return std::nullopt;
  const size_t second = dotted.find('.', first + 1);
  if (second == std::string::npos) return std::nullopt;
  const std::string image = dotted.substr(0, first);
  const std::string region = dotted.substr(first + 1, second - first - 1);
  MetricPath p;
  p.key_ = dotted.substr(second + 1);
  if (image == "visibility")
    p.image_ = &MetricsRecord::visibility;
  else if (image == "shaded")
    p.image_ = &MetricsRecord::shaded;
  if (region == "all")
    p.region_ = [](const ImageMetrics& m) { return &m.all; };
  else if (region == "geometry")
    p.region_ = [](const ImageMetrics& m) { return m.geometry ? &*m.geometry : nullptr; };
  else if (region == "penumbra")
    p.region_ = [](const ImageMetrics& m) { return &m.penumbra; };
  else if (region == "soft_union")
    p.region_ = [](const ImageMetrics& m) { return &m.soft_union; };
  else if (region == "receivers")
    p.region_ = [](const ImageMetrics& m) { return m.receivers ? &*m.receivers : nullptr; };
  else if (region == "terminator")
    p.region_ = [](const ImageMetrics& m) { return m.terminator ? &*m.terminator : nullptr; };
  else if (region == "near_third")
    p.region_ = [](const ImageMetrics& m) { return m.near_third ? &*m.near_third : nullptr; };
  else if (region == "middle_third")
    p.region_ = [](const ImageMetrics& m) { return m.middle_third ? &*m.middle_third : nullptr; };
  else if (region == "far_third")
    p.region_ = [](const ImageMetrics& m) { return m.far_third ? &*m.far_third : nullptr; };
  const bool known = number_of(RegionStats{}, p.key_).has_value();
  if (p.image_ == nullptr || p.region_ == nullptr || !known) return std::nullopt;
  return p;
}

double MetricPath::of(const MetricsRecord& m) const {
  const RegionStats* s = region_(m.*image_);
  if (s == nullptr) return std::numeric_limits<double>::quiet_NaN();
  return number_of(*s, key_).value_or(0.0);  // parse() admits known keys only
}

}  // namespace sb::record
