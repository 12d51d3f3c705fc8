#pragma once
// The catalogue of figures: every number a report, a chart, a comparison or
// the history reads from a job record, with its key, its name in words, its
// unit, which way it improves, its print format and its doc. The per-region
// statistics (RegionStats), the regions (ImageMetrics), the images
// (MetricsRecord) are described once, where their members are
// (record/metrics_record.h); this header lists them in that order, so that
// MetricPath, the report columns, charts, compare, the LaTeX defaults, the
// history and every "expected one of" message read one list. The time series
// are declared here: they are medians of the record's timing, not members of
// their own.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "record/describe.h"
#include "record/metrics_record.h"
#include "record/timing_record.h"

namespace sb::record {

// A number RegionStats holds for one image over one region ("rmse").
struct Statistic {
  std::string key;
  FieldInfo info;
  std::function<double(const RegionStats&)> value;  // NaN where absent (flip_mean)
};

// A region of pixels each image is measured over ("penumbra").
struct Region {
  std::string key;
  FieldInfo info;
  // Its statistics in an image's metrics; null when the record lacks the
  // region (one added after it was written, or one its job did not measure).
  std::function<const RegionStats*(const ImageMetrics&)> of;
  // Its statistics to fill in (an optional region made present).
  std::function<RegionStats&(ImageMetrics&)> slot;
  // Its name in a report column's: "penumbra" of `penumbra_rmse`, "near" of
  // `near_rmse` (the label in lower case, spaces as "_").
  std::string column;
};

// An image measured against the reference's ("visibility").
struct Image {
  std::string key;
  FieldInfo info;
  ImageMetrics MetricsRecord::*member = nullptr;
};

// A number of one image as a whole ("flip_shaded": MetricsRecord's own).
struct WholeImageFigure {
  std::string key;
  FieldInfo info;
  std::function<std::optional<double>(const MetricsRecord&)> value;  // nullopt where absent
};

// A time series of a job: the median of one of its timing's series.
struct TimeSeries {
  const char* key;      // the history's quantity: "time.frame_ratio"
  const char* option;   // its name on the command line: "ratio"
  const char* column;   // its report column: "x_control"
  const char* heading;  // the history report's heading: "frame time / control"
  FieldInfo info;
  // The series, or null when the record has none (no control).
  const Series* (*series)(const TimingRecord&) = nullptr;
};

// In record order (RegionStats::describe): the statistics that are numbers
// (max_pixel, a pair, is not one).
const std::vector<Statistic>& statistics();
// In record order (ImageMetrics::describe).
const std::vector<Region>& regions();
// In record order (MetricsRecord::describe): visibility, shaded.
const std::vector<Image>& images();
// In record order (MetricsRecord::describe): flip_shaded.
const std::vector<WholeImageFigure>& whole_image_figures();
// time.frame_ratio, time.frame_ms, time.technique_ms.
const std::vector<TimeSeries>& time_series();

// By key; null for another key.
const Statistic* find_statistic(std::string_view key);
const Region* find_region(std::string_view key);
const Image* find_image(std::string_view key);
const WholeImageFigure* find_whole_image_figure(std::string_view key);
const TimeSeries* find_time_series(std::string_view key);

// The keys joined: "a|b|c" with `separator` "|", "a, b, c" with ", ".
template <class Figure>
std::string keys_of(const std::vector<Figure>& figures, const char* separator) {
  std::string out;
  for (const Figure& f : figures) {
    if (!out.empty()) out += separator;
    out += f.key;
  }
  return out;
}

// The error a report, a chart, `compare` and the history read unless told
// otherwise: the visibility's over the surface, which does not change with
// framing (docs/results.md, "Regions").
inline constexpr const char* kDefaultErrorMetric = "visibility.geometry.rmse";

// What a metric path may be, for "expected ..." messages:
// "<visibility|shaded>.<all|geometry|...>.<key> with key one of pixel_count,
// rmse, ...".
std::string metric_path_syntax();

}  // namespace sb::record
