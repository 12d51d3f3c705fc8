// The catalogue of figures (record/figures.h) is the one list its readers
// take: every statistic, region and image it holds reaches the schema
// tables, the metric paths, the report columns that show it and the
// "expected ..." messages, each read from the catalogue here, not from a
// second list.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include "core/error.h"
#include "record/figures.h"
#include "record/record_schema.h"
#include "results/compare.h"
#include "results/report_columns.h"

namespace sb {
namespace {

using record::find_region;
using record::find_statistic;
using record::images;
using record::MetricPath;
using record::regions;
using record::statistics;
using record::time_series;

// The rows of one schema table: the text from its heading to the next one.
std::string schema_table(const std::string& name) {
  const std::string all = record::record_schema_markdown();
  const size_t at = all.find("#### " + name + "\n");
  if (at == std::string::npos) return "";
  return all.substr(at, all.find("#### ", at + 1) - at);
}

bool has_row(const std::string& table, const std::string& key) {
  return table.find("| `" + key + "` |") != std::string::npos;
}

TEST(Figures, EveryEntryHasItsRowInTheSchemaTables) {
  const std::string stats = schema_table("RegionStats");
  const std::string regions_table = schema_table("ImageMetrics");
  const std::string images_table = schema_table("MetricsRecord");
  ASSERT_FALSE(stats.empty());
  for (const auto& s : statistics()) EXPECT_TRUE(has_row(stats, s.key)) << s.key;
  for (const auto& r : regions()) EXPECT_TRUE(has_row(regions_table, r.key)) << r.key;
  for (const auto& i : images()) EXPECT_TRUE(has_row(images_table, i.key)) << i.key;
  for (const auto& f : record::whole_image_figures())
    EXPECT_TRUE(has_row(images_table, f.key)) << f.key;
}

TEST(Figures, EveryEntryIsDisplayedAndDocumented) {
  for (const auto& s : statistics()) {
    EXPECT_STRNE(s.info.display.label, "") << s.key;
    EXPECT_NE(s.info.display.format, nullptr) << s.key;
    EXPECT_STRNE(s.info.doc, "") << s.key;
  }
  for (const auto& r : regions()) {
    EXPECT_STRNE(r.info.display.label, "") << r.key;
    EXPECT_FALSE(r.column.empty()) << r.key;
  }
  for (const auto& t : time_series()) {
    EXPECT_STRNE(t.info.display.label, "") << t.key;
    EXPECT_NE(t.info.display.format, nullptr) << t.key;
  }
}

TEST(Figures, EveryImageRegionAndStatisticIsAMetricPath) {
  // Each (image, region) its own pixel count, so that a path reading
  // another one's is seen.
  record::MetricsRecord m;
  std::int64_t count = 0;
  for (const auto& i : images())
    for (const auto& r : regions()) r.slot(m.*i.member).pixel_count = ++count;
  count = 0;
  for (const auto& i : images())
    for (const auto& r : regions()) {
      ++count;
      for (const auto& s : statistics()) {
        const std::string dotted = i.key + "." + r.key + "." + s.key;
        const auto path = MetricPath::parse(dotted);
        ASSERT_TRUE(path.has_value()) << dotted;
        EXPECT_EQ(path->key(), s.key);
        EXPECT_TRUE(path->holds(m)) << dotted;
        const double expected = s.value(*r.of(m.*i.member)), got = path->of(m);
        EXPECT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected))) << dotted;
      }
      EXPECT_EQ(MetricPath::parse(i.key + "." + r.key + ".pixel_count")->of(m), double(count));
    }
  EXPECT_FALSE(MetricPath::parse("visibility.all.nope"));
  EXPECT_FALSE(MetricPath::parse("visibility.nowhere.rmse"));
  EXPECT_FALSE(MetricPath::parse("neither.all.rmse"));
}

TEST(Figures, TheMessageOfAWrongPathListsEveryEntry) {
  const std::string syntax = record::metric_path_syntax();
  for (const auto& i : images()) EXPECT_NE(syntax.find(i.key), std::string::npos) << i.key;
  for (const auto& r : regions()) EXPECT_NE(syntax.find(r.key), std::string::npos) << r.key;
  for (const auto& s : statistics()) EXPECT_NE(syntax.find(s.key), std::string::npos) << s.key;
  results::CompareOptions o;
  o.metric = "visibility.all.nope";
  try {
    results::check_options(o);
    FAIL() << "expected InputError";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(syntax), std::string::npos) << e.what();
  }
}

// A report column of a statistic says what the catalogue says of it.
TEST(Figures, ReportColumnsOfAStatisticTakeItsLabelUnitDirectionAndFormat) {
  std::set<std::string> seen;
  for (const auto& c : results::report_columns()) {
    if (!c.numeric()) continue;
    std::string name = c.name;
    if (name.rfind("second_", 0) == 0) name = name.substr(7);
    const record::Statistic* s = find_statistic(name);
    std::string label = s != nullptr ? s->info.display.label : "";
    for (const auto& r : regions())
      if (name.rfind(r.column + "_", 0) == 0)
        if (const auto* t = find_statistic(name.substr(r.column.size() + 1))) {
          s = t;
          label = std::string(r.info.display.label) + " " + t->info.display.label;
        }
    if (s == nullptr) continue;
    seen.insert(s->key);
    EXPECT_EQ(std::string(c.label).substr(0, label.size()), label) << c.name;
    EXPECT_STREQ(c.unit, s->info.unit) << c.name;
    EXPECT_EQ(c.better, s->info.display.better) << c.name;
    EXPECT_STREQ(c.format, s->info.display.format) << c.name;
  }
  EXPECT_TRUE(seen.count("rmse") && seen.count("psnr") && seen.count("ssim"));
  for (const auto& t : time_series()) {
    const results::ReportColumn& c = results::report_column(t.column);
    EXPECT_STREQ(c.label, t.info.display.label);
    EXPECT_STREQ(c.unit, t.info.unit);
    EXPECT_STREQ(c.format, t.info.display.format);
  }
}

TEST(Figures, FindsByKeyOnly) {
  EXPECT_NE(find_region("penumbra"), nullptr);
  EXPECT_EQ(find_region("rmse"), nullptr);
  EXPECT_NE(find_statistic("frac_over_0.05"), nullptr);
  EXPECT_EQ(find_statistic("max_pixel"), nullptr);  // a pair, not a number
}

}  // namespace
}  // namespace sb
