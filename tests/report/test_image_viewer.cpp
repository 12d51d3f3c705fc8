// The report's image viewer without a browser: its items and image URLs, and
// data files that hold the records' EXRs bit for bit (decoded here with
// OpenSSL's base64 and compared with OpenImageIO's reading of the EXRs), and
// the reference's measured pixels as its mask_all.png has them.
// What a browser does with them: test_html_chromium.cpp.
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../metrics/test_util.h"
#include "report_fixture.h"
#include "results/html_report.h"
#include "results/image_viewer.h"

namespace sb {

using nlohmann::json;

namespace {

namespace fs = std::filesystem;

constexpr const char* kConfigOpen = "<script type=\"application/json\" class=\"viewer-config\">";

std::vector<json> viewer_configs(const std::string& html) {
  std::vector<json> out;
  for (const std::string& text : test::between(html, kConfigOpen, "</script>"))
    out.push_back(json::parse(text));
  return out;
}

std::vector<float> decode_floats(const std::string& b64) {
  std::vector<unsigned char> bytes(b64.size() / 4 * 3 + 3);
  const int n = EVP_DecodeBlock(bytes.data(), reinterpret_cast<const unsigned char*>(b64.data()),
                                static_cast<int>(b64.size()));
  EXPECT_GE(n, 0);
  // EVP_DecodeBlock counts the padding's zero bytes too.
  const size_t real = static_cast<size_t>(n) - (b64.size() >= 2 && b64.end()[-1] == '=') -
                      (b64.size() >= 2 && b64.end()[-2] == '=');
  std::vector<float> out(real / sizeof(float));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(float));
  return out;
}

// The JSON a data file passes to sbViewerData, and the key it passes.
json data_file(const fs::path& path, std::string& key) {
  const std::string text = test::read_text(path);
  const std::string open = "sbViewerData(";
  EXPECT_EQ(text.rfind(open, 0), 0u) << path;
  const size_t comma = text.find("\",");
  key = json::parse(text.substr(open.size(), comma + 1 - open.size())).get<std::string>();
  return json::parse(text.substr(comma + 2, text.rfind(')') - comma - 2));
}

void expect_same_floats(const std::vector<float>& got, const core::ImageF& want,
                        const std::string& what) {
  ASSERT_EQ(got.size(), want.data.size()) << what;
  EXPECT_EQ(std::memcmp(got.data(), want.data.data(), got.size() * sizeof(float)), 0) << what;
}

TEST(report_viewer, ItemsAreTheReferenceThenEveryJobWithImagesInTableOrder) {
  test::TempDir dir("viewer_items");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const std::string html = test::read_text(run.out_dir / "index.html");
  const auto configs = viewer_configs(html);
  ASSERT_EQ(configs.size(), 2u);  // one per scene variant and resolution
  EXPECT_NE(html.find("id=\"viewer-0\""), std::string::npos);
  EXPECT_NE(html.find("id=\"viewer-1\""), std::string::npos);
  const std::vector<std::string> labels = {"reference", "none", "shadow_map/size=1024",
                                           "pcf_box/k=3,size=1024", "vsm/k=9,prefilter=gauss"};
  for (size_t g = 0; g < configs.size(); ++g) {
    const json& c = configs[g];
    EXPECT_EQ(c["width"], g == 0 ? 64 : 96);
    EXPECT_EQ(c["reference"], 0);
    EXPECT_DOUBLE_EQ(c["full_scale"].get<double>(), 0.25);
    ASSERT_EQ(c["items"].size(), labels.size());  // the skipped job has no image
    for (size_t i = 0; i < labels.size(); ++i) {
      const json& item = c["items"][i];
      EXPECT_EQ(item["label"], labels[i]);
      for (const char* k : {"shaded", "error", "flip"}) {
        const std::string url = item[k];
        if (!url.empty()) {
          EXPECT_TRUE(fs::is_regular_file(run.out_dir / url)) << url;
        }
      }
      EXPECT_FALSE(item["shaded"].get<std::string>().empty());
      EXPECT_EQ(item["error"].get<std::string>().empty(), i == 0);  // the reference has none
    }
    // The heat map's colours at 256 steps: black at 0, pale yellow at full scale.
    ASSERT_EQ(c["lut"].size(), 768u);
    EXPECT_EQ(c["lut"][0], 0);
    EXPECT_EQ(c["lut"][765], 252);
    EXPECT_EQ(c["lut"][767], 164);
  }
}

TEST(report_viewer, DataFilesHoldTheRecordsExrsBitForBit) {
  test::TempDir dir("viewer_data");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const auto configs = viewer_configs(test::read_text(run.out_dir / "index.html"));
  ASSERT_EQ(configs.size(), 2u);
  size_t files = 0;
  for (size_t g = 0; g < configs.size(); ++g) {
    const json& items = configs[g]["items"];
    for (size_t i = 0; i < items.size(); ++i) {
      const std::string url = items[i]["data"];
      ASSERT_FALSE(url.empty()) << items[i]["label"];
      std::string key;
      const json d = data_file(run.out_dir / url, key);
      EXPECT_EQ(key, url);  // the script finds the data by the file's URL
      // The record whose EXR it is: the reference's, or the job's by label.
      const record::JobRecord* r = nullptr;
      for (const auto& rec : run.records)
        if (rec.width == configs[g]["width"] &&
            (i == 0 ? rec.images.reference_visibility.has_value()
                    : rec.technique_variant == items[i]["label"]))
          r = &rec;
      ASSERT_NE(r, nullptr) << items[i]["label"];
      const auto& im = r->images;
      const core::ImageF v = metrics::io::read_image(
          (run.run_dir / (i == 0 ? *im.reference_visibility : *im.visibility)).string());
      EXPECT_EQ(d["width"], v.width);
      EXPECT_EQ(d["height"], v.height);
      EXPECT_EQ(d["channels"], v.channels);
      expect_same_floats(decode_floats(d["v"]), v, url + " V");
      if (i == 0) {
        const core::ImageF sigma =
            metrics::io::read_image((run.run_dir / *im.reference_std_error).string());
        expect_same_floats(decode_floats(d["sigma"]), sigma, url + " sigma");
        // The measured pixels, one byte each: 1 where mask_all.png is 255.
        const core::ImageF mask =
            metrics::io::read_image((run.run_dir / im.masks.at("all")).string());
        const std::string b64 = d["measured"];
        std::vector<unsigned char> bytes(b64.size() / 4 * 3 + 3);
        EVP_DecodeBlock(bytes.data(), reinterpret_cast<const unsigned char*>(b64.data()),
                        static_cast<int>(b64.size()));
        size_t in = 0;
        for (size_t p = 0; p < mask.pixel_count(); ++p) {
          ASSERT_EQ(bytes[p], mask.data[p] > 0.5f ? 1 : 0) << p;
          in += bytes[p];
        }
        EXPECT_EQ(in, static_cast<size_t>((v.width - 4) * v.height));
      } else {
        EXPECT_FALSE(d.contains("sigma"));
        EXPECT_FALSE(d.contains("measured"));
      }
      ++files;
    }
  }
  EXPECT_EQ(files, 10u);
}

TEST(report_viewer, WithoutDataNoFileIsWrittenAndStaleOnesAreRemoved) {
  test::TempDir dir("viewer_nodata");
  const auto run = test::make_synthetic_run(dir.path());
  const fs::path stale = run.out_dir / results::kViewerDataDir / "7-7.js";
  fs::create_directories(stale.parent_path());
  test::write_text(stale, "sbViewerData('old', {});\n");
  results::write_html_report(run.records, run.run_dir.string(), run.out_dir.string(), run.charts,
                             "no data", false);
  EXPECT_FALSE(fs::exists(run.out_dir / results::kViewerDataDir));
  for (const json& c : viewer_configs(test::read_text(run.out_dir / "index.html")))
    for (const json& item : c["items"]) EXPECT_EQ(item["data"], "") << item["label"];

  test::write_synthetic_report(run);  // with data: only this report's files
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(run.out_dir / results::kViewerDataDir / "0-0.js"));
}

TEST(report_viewer, AMissingExrLeavesItsItemWithoutData) {
  test::TempDir dir("viewer_missing");
  const auto run = test::make_synthetic_run(dir.path());
  fs::remove(run.run_dir / *run.records[1].images.visibility);  // shadow_map @ 64x48
  test::write_synthetic_report(run);
  const auto configs = viewer_configs(test::read_text(run.out_dir / "index.html"));
  ASSERT_EQ(configs.size(), 2u);
  EXPECT_EQ(configs[0]["items"][2]["label"], "shadow_map/size=1024");
  EXPECT_EQ(configs[0]["items"][2]["data"], "");
  EXPECT_NE(configs[0]["items"][1]["data"], "");
  EXPECT_NE(configs[1]["items"][2]["data"], "");
}

TEST(report_viewer, ALabelCannotEndTheConfigScript) {
  test::TempDir dir("viewer_label");
  auto run = test::make_synthetic_run(dir.path());
  run.records[1].technique_variant = "x</script><b>bold</b>";
  test::write_synthetic_report(run);
  const std::string html = test::read_text(run.out_dir / "index.html");
  size_t opens = 0, closes = 0;
  for (size_t p = html.find("<script"); p != std::string::npos; p = html.find("<script", p + 1))
    ++opens;
  for (size_t p = html.find("</script>"); p != std::string::npos; p = html.find("</script>", p + 1))
    ++closes;
  EXPECT_EQ(opens, closes);
  const auto configs = viewer_configs(html);
  ASSERT_EQ(configs.size(), 2u);
  EXPECT_EQ(configs[0]["items"][2]["label"], "x</script><b>bold</b>");
  // Nowhere raw: in the JSON '<' and '>' are \u003c and \u003e (which
  // JSON reads as the label, above), in the buttons &lt; and &gt;.
  EXPECT_EQ(html.find("<b>bold"), std::string::npos);
  EXPECT_NE(html.find("\\u003cb\\u003ebold"), std::string::npos);
}

}  // namespace
}  // namespace sb
