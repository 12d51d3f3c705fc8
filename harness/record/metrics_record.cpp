#include "record/metrics_record.h"

#include <limits>
#include <vector>

#include "record/figures.h"
#include "record/record_json.h"

namespace sb::record {

using json = nlohmann::json;

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
  const Image* image = find_image(std::string_view(dotted).substr(0, first));
  const Region* region =
      find_region(std::string_view(dotted).substr(first + 1, second - first - 1));
  const Statistic* statistic = find_statistic(std::string_view(dotted).substr(second + 1));
  if (image == nullptr || region == nullptr || statistic == nullptr) return std::nullopt;
  MetricPath p;
  p.image_ = image;
  p.region_ = region;
  p.statistic_ = statistic;
  return p;
}

bool MetricPath::holds(const MetricsRecord& m) const {
  return region_->of(m.*image_->member) != nullptr;
}

const std::string& MetricPath::key() const { return statistic_->key; }

bool MetricPath::higher_is_better() const {
  return statistic_->info.display.better == Better::Higher;
}

double MetricPath::of(const MetricsRecord& m) const {
  const RegionStats* s = region_->of(m.*image_->member);
  if (s == nullptr) return std::numeric_limits<double>::quiet_NaN();
  return statistic_->value(*s);
}

}  // namespace sb::record
