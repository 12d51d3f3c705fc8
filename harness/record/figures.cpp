#include "record/figures.h"

#include <cctype>
#include <limits>
#include <type_traits>

namespace sb::record {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// RegionStats' members that are numbers, as statistics.
struct StatisticLister {
  std::vector<Statistic> out;

  template <class M>
  void field(const char* key, M RegionStats::*member, const FieldInfo& info = {}) {
    if constexpr (std::is_arithmetic_v<M>)
      out.push_back(
          {key, info, [member](const RegionStats& s) { return static_cast<double>(s.*member); }});
    else if constexpr (std::is_same_v<M, std::optional<double>>)
      out.push_back(
          {key, info, [member](const RegionStats& s) { return (s.*member).value_or(kNaN); }});
  }
  template <class W, class R>
  void custom(const char*, const char*, const FieldInfo&, W&&, R&&) {}
};

// "Soft union" → "soft_union".
std::string column_of(const char* label) {
  std::string out;
  for (const char* c = label; *c != '\0'; ++c)
    out += *c == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(*c)));
  return out;
}

// ImageMetrics' members, as regions.
struct RegionLister {
  std::vector<Region> out;

  void field(const char* key, RegionStats ImageMetrics::*member, const FieldInfo& info) {
    out.push_back({key, info, [member](const ImageMetrics& m) { return &(m.*member); },
                   [member](ImageMetrics& m) -> RegionStats& { return m.*member; },
                   column_of(info.display.label)});
  }
  void field(const char* key, std::optional<RegionStats> ImageMetrics::*member,
             const FieldInfo& info) {
    out.push_back({key, info,
                   [member](const ImageMetrics& m) {
                     return (m.*member).has_value() ? &*(m.*member) : nullptr;
                   },
                   [member](ImageMetrics& m) -> RegionStats& {
                     if (!(m.*member)) (m.*member).emplace();
                     return *(m.*member);
                   },
                   column_of(info.display.label)});
  }
};

// MetricsRecord's images and its numbers of a whole image.
struct ImageLister {
  std::vector<Image> images;
  std::vector<WholeImageFigure> whole;

  void field(const char* key, ImageMetrics MetricsRecord::*member, const FieldInfo& info) {
    images.push_back({key, info, member});
  }
  void field(const char* key, std::optional<double> MetricsRecord::*member, const FieldInfo& info) {
    whole.push_back({key, info, [member](const MetricsRecord& m) { return m.*member; }});
  }
};

const ImageLister& image_lister() {
  static const ImageLister l = [] {
    ImageLister out;
    MetricsRecord::describe(out);
    return out;
  }();
  return l;
}

template <class Figure>
const Figure* find(const std::vector<Figure>& figures, std::string_view key) {
  for (const Figure& f : figures)
    if (f.key == key) return &f;
  return nullptr;
}

}  // namespace

const std::vector<Statistic>& statistics() {
  static const std::vector<Statistic> list = [] {
    StatisticLister l;
    RegionStats::describe(l);
    return std::move(l.out);
  }();
  return list;
}

const std::vector<Region>& regions() {
  static const std::vector<Region> list = [] {
    RegionLister l;
    ImageMetrics::describe(l);
    return std::move(l.out);
  }();
  return list;
}

const std::vector<Image>& images() { return image_lister().images; }

const std::vector<WholeImageFigure>& whole_image_figures() { return image_lister().whole; }

const std::vector<TimeSeries>& time_series() {
  constexpr Better lower = Better::Lower;
  static const std::vector<TimeSeries> list = {
      {"time.frame_ratio",
       "ratio",
       "x_control",
       "frame time / control",
       {.doc = "the job's frames over the control's next to them "
               "(timing.control.frame_ratio.median): comparable across hosts",
        .display = {"Frame / control", lower, "%.3f"}},
       [](const TimingRecord& t) -> const Series* {
         return t.control ? &t.control->frame_ratio : nullptr;
       }},
      {"time.frame_ms",
       "frame_ms",
       "frame_ms",
       "frame time (ms)",
       {.unit = "ms",
        .doc = "the frame's median time (timing.frame.median_ms, this host only)",
        .display = {"Frame", lower, "%.3f"}},
       [](const TimingRecord& t) -> const Series* { return &t.frame; }},
      {"time.technique_ms",
       "technique_ms",
       "technique_ms",
       "technique time (ms)",
       {.unit = "ms",
        .doc = "the technique's median time (timing.technique.median_ms, this host only)",
        .display = {"Technique", lower, "%.3f"}},
       [](const TimingRecord& t) -> const Series* { return &t.technique; }},
  };
  return list;
}

const Statistic* find_statistic(std::string_view key) { return find(statistics(), key); }
const Region* find_region(std::string_view key) { return find(regions(), key); }
const Image* find_image(std::string_view key) { return find(images(), key); }
const WholeImageFigure* find_whole_image_figure(std::string_view key) {
  return find(whole_image_figures(), key);
}
const TimeSeries* find_time_series(std::string_view key) {
  for (const TimeSeries& t : time_series())
    if (key == t.key) return &t;
  return nullptr;
}

std::string metric_path_syntax() {
  return "<" + keys_of(images(), "|") + ">.<" + keys_of(regions(), "|") +
         ">.<key> with key one of " + keys_of(statistics(), ", ");
}

}  // namespace sb::record
