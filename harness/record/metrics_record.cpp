#include "record/metrics_record.h"

#include <limits>
#include <vector>

namespace sb {

using json = nlohmann::json;

namespace {

// The numbers of RegionStats by their record keys (max_pixel is a pair).
struct NumberKey {
  const char* key;
  double (*get)(const RegionStats&);
};

const NumberKey kNumberKeys[] = {
    {"pixel_count", [](const RegionStats& s) { return static_cast<double>(s.pixel_count); }},
    {"rmse", [](const RegionStats& s) { return s.rmse; }},
    {"mae", [](const RegionStats& s) { return s.mae; }},
    {"max_error", [](const RegionStats& s) { return s.max_error; }},
    {"psnr", [](const RegionStats& s) { return s.psnr; }},
    {"ssim", [](const RegionStats& s) { return s.ssim; }},
    {"frac_over_0.01", [](const RegionStats& s) { return s.frac_over_001; }},
    {"frac_over_0.05", [](const RegionStats& s) { return s.frac_over_005; }},
    {"frac_over_0.1", [](const RegionStats& s) { return s.frac_over_01; }},
    {"nonfinite_count",
     [](const RegionStats& s) { return static_cast<double>(s.nonfinite_count); }},
    {"mean_signed", [](const RegionStats& s) { return s.mean_signed; }},
};

}  // namespace

json RegionStats::to_json() const {
  return {{"pixel_count", pixel_count},
          {"rmse", json_number(rmse)},
          {"mae", json_number(mae)},
          {"max_error", json_number(max_error)},
          {"max_pixel", json::array({max_x, max_y})},
          {"psnr", json_number(psnr)},
          {"ssim", json_number(ssim)},
          {"frac_over_0.01", json_number(frac_over_001)},
          {"frac_over_0.05", json_number(frac_over_005)},
          {"frac_over_0.1", json_number(frac_over_01)},
          {"nonfinite_count", nonfinite_count},
          {"mean_signed", json_number(mean_signed)}};
}

RegionStats RegionStats::from_json(const Fields& f) {
  RegionStats s;
  s.pixel_count = f.get<std::int64_t>("pixel_count");
  s.rmse = f.get<double>("rmse");
  s.mae = f.get<double>("mae");
  s.max_error = f.get<double>("max_error");
  const std::vector<int> max_pixel = f.get<std::vector<int>>("max_pixel");
  if (max_pixel.size() != 2) f.fail("max_pixel", "expected [x, y]");
  s.max_x = max_pixel[0];
  s.max_y = max_pixel[1];
  s.psnr = f.get<double>("psnr");
  s.ssim = f.get<double>("ssim");
  s.frac_over_001 = f.get<double>("frac_over_0.01");
  s.frac_over_005 = f.get<double>("frac_over_0.05");
  s.frac_over_01 = f.get<double>("frac_over_0.1");
  s.nonfinite_count = f.get<std::int64_t>("nonfinite_count");
  s.mean_signed = f.get<double>("mean_signed");
  return s;
}

json ImageMetrics::to_json() const {
  json j = {{"all", all.to_json()},
            {"penumbra", penumbra.to_json()},
            {"soft_union", soft_union.to_json()}};
  if (geometry) j["geometry"] = geometry->to_json();
  if (receivers) j["receivers"] = receivers->to_json();
  if (near_third) j["near_third"] = near_third->to_json();
  if (middle_third) j["middle_third"] = middle_third->to_json();
  if (far_third) j["far_third"] = far_third->to_json();
  return j;
}

ImageMetrics ImageMetrics::from_json(const Fields& f) {
  ImageMetrics m{RegionStats::from_json(f.object("all")),
                 RegionStats::from_json(f.object("penumbra")),
                 RegionStats::from_json(f.object("soft_union"))};
  if (f.has("geometry")) m.geometry = RegionStats::from_json(f.object("geometry"));
  if (f.has("receivers")) m.receivers = RegionStats::from_json(f.object("receivers"));
  if (f.has("near_third")) m.near_third = RegionStats::from_json(f.object("near_third"));
  if (f.has("middle_third")) m.middle_third = RegionStats::from_json(f.object("middle_third"));
  if (f.has("far_third")) m.far_third = RegionStats::from_json(f.object("far_third"));
  return m;
}

json MetricsRecord::to_json() const {
  return {{"visibility", visibility.to_json()}, {"shaded", shaded.to_json()}};
}

MetricsRecord MetricsRecord::from_json(const Fields& f) {
  return {ImageMetrics::from_json(f.object("visibility")),
          ImageMetrics::from_json(f.object("shaded"))};
}

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
  else if (region == "near_third")
    p.region_ = [](const ImageMetrics& m) { return m.near_third ? &*m.near_third : nullptr; };
  else if (region == "middle_third")
    p.region_ = [](const ImageMetrics& m) { return m.middle_third ? &*m.middle_third : nullptr; };
  else if (region == "far_third")
    p.region_ = [](const ImageMetrics& m) { return m.far_third ? &*m.far_third : nullptr; };
  bool known = false;
  for (const auto& k : kNumberKeys) known = known || p.key_ == k.key;
  if (p.image_ == nullptr || p.region_ == nullptr || !known) return std::nullopt;
  return p;
}

double MetricPath::of(const MetricsRecord& m) const {
  const RegionStats* s = region_(m.*image_);
  if (s == nullptr) return std::numeric_limits<double>::quiet_NaN();
  for (const auto& k : kNumberKeys)
    if (key_ == k.key) return k.get(*s);
  return 0.0;  // parse() admits known keys only
}

}  // namespace sb
