// The report's image viewer in headless Chromium, driven as a person would:
// a copy of the page with a script that presses keys (3, then the arrows, v
// for V), turns the wheel over the canvas (zoom 8x), points at a pixel and
// reads the readout; then splits against the reference (c) at +1 EV (] ]) and
// reads again. The values must be the records' EXRs at that pixel (read here
// with OpenImageIO), and a screenshot of the same steps must show those
// pixels as blocks of one grey (nearest neighbour) at the exposure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "../common/chromium.h"
#include "../metrics/test_util.h"
#include "report_fixture.h"

namespace sb {

using core::ImageF;
using nlohmann::json;
using test::BrowserRun;
using test::find_chromium;
using test::joined;
using test::run_chromium;

namespace {

namespace fs = std::filesystem;

constexpr const char* kDriver = R"(<script>
(function () {
  var v = document.querySelector('section.viewer');
  document.body.insertBefore(v, document.body.firstChild);  // at the top: no scrolling
  v.focus();
  var log = {};
  function key(k) {
    v.dispatchEvent(new KeyboardEvent('keydown', {key: k, bubbles: true, cancelable: true}));
  }
  key('3'); log.after3 = v.dataset.item;
  key('ArrowRight'); log.afterRight = v.dataset.item;
  key('ArrowLeft'); log.afterLeft = v.dataset.item;
  key('v'); log.mode = v.dataset.mode;
  var c = v.querySelector('canvas'), r = c.getBoundingClientRect();
  var px = Math.round(r.left + r.width * 0.6), py = Math.round(r.top + r.height * 0.4);
  for (var i = 0; i < 3; ++i)
    c.dispatchEvent(new WheelEvent('wheel', {deltaY: -100, clientX: px, clientY: py,
                                             bubbles: true, cancelable: true}));
  function readout() {
    c.dispatchEvent(new MouseEvent('mousemove', {clientX: px, clientY: py, bubbles: true}));
    var d = v.querySelector('.viewer-readout').dataset;
    return {x: d.x, y: d.y, item: d.item, v: d.v, vref: d.vref, error: d.error, sigma: d.sigma,
            text: v.querySelector('.viewer-readout').textContent};
  }
  function whenReady(then, tries) {
    if (v.dataset.state === 'ready' || tries > 250) then();
    else setTimeout(function () { whenReady(then, tries + 1); }, 20);
  }
  whenReady(function () {
    log.a = readout();
    key('c'); key(']'); key(']');
    whenReady(function () {
      log.b = readout();
      log.state = v.dataset.state;
      log.scale = Number(v.dataset.scale); log.fit = Number(v.dataset.fit);
      log.offset = v.dataset.offset.split(',').map(Number);
      log.canvas = {left: r.left, top: r.top, cssWidth: r.width, width: c.width, height: c.height};
      log.px = px; log.py = py; log.dpr = window.devicePixelRatio;
      document.body.dataset.viewerTest = JSON.stringify(log);
    }, 0);
  }, 0);
})();
</script>
</body>)";

using viewer_chromium = test::ChromiumTest;

// The page's DOM attribute holding the driver's log, unescaped.
json driver_log(const std::string& dom) {
  const std::string open = "data-viewer-test=\"";
  const size_t p = dom.find(open);
  if (p == std::string::npos) return nullptr;
  std::string text = dom.substr(p + open.size(), dom.find('"', p + open.size()) - p - open.size());
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"&quot;", "\""},
                                 {"&lt;", "<"},
                                 {"&gt;", ">"},
                                 {"&amp;", "&"}})
    for (size_t q = text.find(from); q != std::string::npos; q = text.find(from, q))
      text.replace(q, from.size(), to);
  return json::parse(text);
}

float value_at(const ImageF& img, int x, int y) { return img.at(x, y, 0); }

// The grey the viewer draws for V at an exposure (linear, clamped).
int grey(float v, double gain) {
  return static_cast<int>(std::lround(std::clamp(double(v) * gain, 0.0, 1.0) * 255.0));
}

// A copy of the report with `driver` in place of </body>.
fs::path probe_page(const test::SyntheticRun& run, const std::string& driver) {
  std::string html = test::read_text(run.out_dir / "index.html");
  const size_t end = html.rfind("</body>");
  EXPECT_NE(end, std::string::npos);
  html.replace(end, 7, driver);
  const fs::path page = run.out_dir / "viewer_probe.html";
  test::write_text(page, html);
  return page;
}

// One size for the DOM run and the screenshot, so that both lay out alike.
constexpr const char* kWindow = "--window-size=1280,1000 --force-device-scale-factor=1 ";

// The driver's log from a --dump-dom run of the page (null, with a failure
// said, when Chromium failed, the page logged anything or the driver did not
// finish).
json run_driver(const std::string& chromium, const fs::path& work, const fs::path& page) {
  const BrowserRun dom = run_chromium(chromium, work, page, std::string(kWindow) + "--dump-dom");
  EXPECT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_TRUE(dom.console.empty()) << joined(dom.console);
  json log = driver_log(dom.dom);
  if (!log.is_object()) ADD_FAILURE() << "the driver did not finish:\n" << dom.dom.substr(0, 3000);
  return log;
}

// The screenshot of the page after the driver's steps.
ImageF screenshot(const std::string& chromium, const fs::path& work, const fs::path& page) {
  const fs::path shot = work / "viewer.png";
  const BrowserRun s =
      run_chromium(chromium, work, page,
                   std::string(kWindow) + "--screenshot=" + test::shell_quote(shot.string()));
  EXPECT_EQ(s.exit_code, 0) << s.log;
  return metrics::io::read_image(shot.string());
}

// The synthetic run's shadow_map at 64x48 (item 2 of the first viewer) and
// its reference, as OpenImageIO reads them.
struct ShadowMapImages {
  explicit ShadowMapImages(const test::SyntheticRun& run) : job(run.records[1]) {
    auto read = [&](const std::optional<std::string>& rel) {
      return metrics::io::read_image((run.run_dir / rel.value()).string());
    };
    v = read(job.images.visibility);
    vref = read(job.images.reference_visibility);
    sigma = read(job.images.reference_std_error);
    error_png = read(job.images.error_heatmap);
  }
  const record::JobRecord& job;
  ImageF v, vref, sigma, error_png;
};

TEST_F(viewer_chromium, FlipsZoomsAndReadsThePixelsOfTheRecordsExrs) {
  test::TempDir dir("viewer_chromium");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const fs::path page = probe_page(run, kDriver);

  const json log = run_driver(chromium_, dir.path(), page);
  ASSERT_TRUE(log.is_object());
  SCOPED_TRACE(log.dump());

  // Items: 0 reference, 1 none, 2 shadow_map, 3 pcf_box, 4 vsm (64x48).
  EXPECT_EQ(log["after3"], "2");
  EXPECT_EQ(log["afterRight"], "3");
  EXPECT_EQ(log["afterLeft"], "2");
  EXPECT_EQ(log["mode"], "v");
  EXPECT_EQ(log["state"], "ready");
  ASSERT_EQ(log["dpr"], 1);
  const double fit = log["fit"], scale = log["scale"];
  EXPECT_DOUBLE_EQ(scale, 8 * fit);  // three wheel steps

  // The pixel under the cursor: zooming about the cursor keeps it there.
  const double cx = (log["px"].get<double>() - log["canvas"]["left"].get<double>()) *
                    log["canvas"]["width"].get<double>() / log["canvas"]["cssWidth"].get<double>();
  const double cy = log["py"].get<double>() - log["canvas"]["top"].get<double>();
  const int x = static_cast<int>(std::floor(cx / fit)), y = static_cast<int>(std::floor(cy / fit));
  const json& a = log["a"];
  ASSERT_EQ(a["x"], std::to_string(x));
  ASSERT_EQ(a["y"], std::to_string(y));
  EXPECT_EQ(a["item"], "2");

  const ShadowMapImages im(run);
  ASSERT_EQ(im.job.technique_variant, "shadow_map/size=1024");
  const ImageF &v = im.v, &vref = im.vref, &sigma = im.sigma;
  // JavaScript prints the float's exact double in the fewest digits that
  // read back as it: equal as doubles, not merely close.
  EXPECT_EQ(std::stod(a["v"].get<std::string>()), double(value_at(v, x, y)));
  EXPECT_EQ(std::stod(a["vref"].get<std::string>()), double(value_at(vref, x, y)));
  EXPECT_EQ(std::stod(a["sigma"].get<std::string>()), double(value_at(sigma, x, y)));
  EXPECT_EQ(std::stod(a["error"].get<std::string>()),
            double(std::fabs(value_at(v, x, y) - value_at(vref, x, y))));
  EXPECT_NE(a["text"].get<std::string>().find("shadow_map/size=1024 (" + std::to_string(x)),
            std::string::npos);

  // Split against the reference: the cursor is right of the line, on it.
  const json& b = log["b"];
  EXPECT_EQ(b["item"], "0");
  EXPECT_EQ(b["x"], a["x"]);
  EXPECT_EQ(std::stod(b["v"].get<std::string>()), double(value_at(vref, x, y)));

  // The same steps, seen: the screenshot's pixels are the greys of V at
  // +1 EV, the reference right of the split and shadow_map left of it, each
  // image pixel a uniform block of `scale` screen pixels.
  const ImageF img = screenshot(chromium_, dir.path(), page);
  auto screen_grey = [&](int sx, int sy) {
    return static_cast<int>(std::lround(img.at(sx, sy, 1) * 255.0f));  // green: R = G = B
  };
  const double ox = log["offset"][0], oy = log["offset"][1];
  const double left = log["canvas"]["left"], top = log["canvas"]["top"];
  // The centre of image pixel (ix, iy) on the screen.
  auto centre = [&](int ix, int iy) {
    return std::pair<int, int>{static_cast<int>(left + (ix + 0.5 - ox) * scale),
                               static_cast<int>(top + (iy + 0.5 - oy) * scale)};
  };
  const int half = static_cast<int>(scale / 2) - 2;
  ASSERT_GT(half, 4);
  auto expect_block = [&](int ix, int iy, int want, const char* what) {
    const auto [sx, sy] = centre(ix, iy);
    ASSERT_GE(sx - half, 0);
    ASSERT_LT(sx + half, img.width);
    for (int dy = -half; dy <= half; dy += half)
      for (int dx = -half; dx <= half; dx += half)
        EXPECT_NEAR(screen_grey(sx + dx, sy + dy), want, 1)
            << what << " pixel (" << ix << ", " << iy << ") at screen (" << sx + dx << ", "
            << sy + dy << ")";
  };
  expect_block(x, y, grey(value_at(vref, x, y), 2.0), "reference");
  expect_block(x + 1, y, grey(value_at(vref, x + 1, y), 2.0), "reference");
  // Left of the split (the canvas's middle): shadow_map.
  const int xl =
      static_cast<int>(std::floor(ox + 0.2 * log["canvas"]["width"].get<double>() / scale));
  expect_block(xl, y, grey(value_at(v, xl, y), 2.0), "shadow_map");
  EXPECT_NE(grey(value_at(v, xl, y), 2.0), grey(value_at(v, xl + 1, y), 2.0));
  expect_block(xl + 1, y, grey(value_at(v, xl + 1, y), 2.0), "shadow_map");
}

// The error view at 0 EV, drawn from the EXRs, is error.png: every image
// pixel's block on a screenshot has error.png's colour to 1 in 255, the
// unmeasured columns (where V differs but error.png is black) included,
// and the readout there says so.
TEST_F(viewer_chromium, ErrorViewAtZeroEvIsTheErrorPng) {
  test::TempDir dir("viewer_chromium_error");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const fs::path page = probe_page(run, R"(<script>
(function () {
  var v = document.querySelector('section.viewer');
  document.body.insertBefore(v, document.body.firstChild);
  v.focus();
  v.dispatchEvent(new KeyboardEvent('keydown', {key: '3', bubbles: true}));
  v.dispatchEvent(new KeyboardEvent('keydown', {key: 'e', bubbles: true}));
  var c = v.querySelector('canvas');
  function done() {
    if (v.dataset.state !== 'ready') { setTimeout(done, 20); return; }
    var r = c.getBoundingClientRect(), s = Number(v.dataset.scale);
    c.dispatchEvent(new MouseEvent('mousemove', {clientX: r.left + 62.5 * s,
                                                 clientY: r.top + 20.5 * s, bubbles: true}));
    var d = v.querySelector('.viewer-readout').dataset;
    document.body.dataset.viewerTest = JSON.stringify({
        left: r.left, top: r.top, scale: s, mode: v.dataset.mode, item: v.dataset.item,
        x: d.x, y: d.y, measured: d.measured || 'true', error: d.error});
  }
  done();
})();
</script>
</body>)");
  const json log = run_driver(chromium_, dir.path(), page);
  ASSERT_TRUE(log.is_object());
  SCOPED_TRACE(log.dump());
  EXPECT_EQ(log["mode"], "error");
  EXPECT_EQ(log["item"], "2");

  const ShadowMapImages im(run);
  const ImageF &v = im.v, &vref = im.vref, &error_png = im.error_png;
  // The readout at (62, 20): unmeasured, though V differs there.
  EXPECT_EQ(log["x"], "62");
  EXPECT_EQ(log["y"], "20");
  EXPECT_EQ(log["measured"], "false");
  EXPECT_GT(std::fabs(value_at(v, 62, 20) - value_at(vref, 62, 20)), 0.01f);

  const ImageF img = screenshot(chromium_, dir.path(), page);
  const double scale = log["scale"], left = log["left"], top = log["top"];
  ASSERT_GE(scale, 4.0);
  int compared = 0, coloured = 0, worst = 0;
  for (int y = 0; y < v.height; ++y) {
    const int sy = static_cast<int>(top + (y + 0.5) * scale);
    if (sy < top + 20) continue;  // under the image's name
    for (int x = 0; x < v.width; ++x) {
      const int sx = static_cast<int>(left + (x + 0.5) * scale);
      ASSERT_LT(sx, img.width);
      ASSERT_LT(sy, img.height);
      bool black = true;
      for (int c = 0; c < 3; ++c) {
        const int want = static_cast<int>(std::lround(error_png.at(x, y, c) * 255.0f));
        const int got = static_cast<int>(std::lround(img.at(sx, sy, c) * 255.0f));
        worst = std::max(worst, std::abs(got - want));
        black = black && want == 0;
      }
      ++compared;
      coloured += black ? 0 : 1;
    }
  }
  EXPECT_LE(worst, 1);
  EXPECT_GT(compared, 2500);
  EXPECT_GT(coloured, 1000);  // not a black image compared with a black one
  for (int y = 4; y < v.height; ++y)
    for (int x = v.width - 4; x < v.width; ++x) EXPECT_EQ(error_png.at(x, y, 0), 0.0f);
}

}  // namespace
}  // namespace sb
