#include "results/image_viewer.h"

#include <openssl/evp.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>

#include "core/atomic_file.h"
#include "core/folder_file.h"
#include "core/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "results/html_page.h"

namespace sb::results {

namespace {

namespace fs = std::filesystem;
using core::ImageF;
using nlohmann::json;
using record::JobRecord;

std::string base64(const void* data, size_t n) {
  std::string out(4 * ((n + 2) / 3), '\0');
  const int written = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                      static_cast<const unsigned char*>(data), static_cast<int>(n));
  out.resize(static_cast<size_t>(written));
  return out;
}

// Float32 planes as base64 of their little-endian bytes (the script reads
// them into a Float32Array, which is little-endian on every browser's CPU).
std::string base64_floats(const std::vector<float>& values) {
  return base64(values.data(), values.size() * sizeof(float));
}

// An image the record names (an EXR, or a mask's PNG), or nothing when it is not there (`run
// --no-images`, a folder cleaned up); an unreadable one, or one the record names outside its
// run folder (absolute, "..", through a symbolic link: core/folder_file.h), is said on stderr
// and left out, so that no file from elsewhere reaches viewer/*.js.
std::optional<ImageF> read_named_image(const fs::path& run_dir,
                                       const std::optional<std::string>& rel) {
  if (!rel) return std::nullopt;
  try {
    const std::optional<core::FolderFile> file = core::open_in_folder(run_dir.string(), *rel);
    if (!file) return std::nullopt;
    return metrics::io::read_image(file->path());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "report: the viewer leaves out %s\n", e.what());
    return std::nullopt;
  }
}

// The heat-map ramp at 256 steps, through the very function the heat maps
// use, so that the error the script draws has error.png's colours.
json heat_lut() {
  json lut = json::array();
  for (int i = 0; i < 256; ++i) {
    float rgb[3];
    metrics::heatmap_colour(static_cast<float>(i) / 255.0f, rgb);
    for (const float c : rgb) lut.push_back(std::lround(c * 255.0f));
  }
  return lut;
}

class ViewerWriter {
 public:
  ViewerWriter(const ViewerGroup& group, const fs::path& run_dir, const fs::path& out_dir,
               const fs::path& run_from_out, bool write_data)
      : group_(group),
        run_dir_(run_dir),
        out_dir_(out_dir),
        run_from_out_(run_from_out),
        write_data_(write_data) {}

  std::string markup() {
    json items = json::array();
    int reference = -1;
    double full_scale = 0.0;
    int width = 0, height = 0;
    for (const JobRecord* r : group_.jobs) {
      if (width == 0 && r->width > 0) width = r->width, height = r->height;
      if (full_scale == 0.0 && r->images.error_heatmap_full_scale)
        full_scale = *r->images.error_heatmap_full_scale;
      if (reference < 0 && (r->images.reference_shaded || r->images.reference_visibility)) {
        reference = static_cast<int>(items.size());
        items.push_back(reference_item(*r, items.size()));
      }
    }
    for (const JobRecord* r : group_.jobs) {
      const auto& im = r->images;
      if (!im.shaded && !im.visibility && !im.error_heatmap && !im.flip_shaded) continue;
      items.push_back(job_item(*r, items.size()));
    }
    if (items.empty()) return "";
    const json config = {{"width", width},         {"height", height}, {"full_scale", full_scale},
                         {"reference", reference}, {"items", items},   {"lut", heat_lut()}};
    return render(config);
  }

 private:
  std::string url(const std::optional<std::string>& rel) const {
    if (!rel) return "";
    return url_path((run_from_out_ / *rel).lexically_normal().generic_string());
  }

  // Writes the item's data file when it has V; its URL, or "" without one.
  // The reference's data also hold its measured pixels (the region "all",
  // one byte each), outside which error.png shows no error.
  std::string data_file(size_t item, const std::optional<ImageF>& v,
                        const std::optional<ImageF>& sigma,
                        const std::optional<ImageF>& measured = std::nullopt) const {
    if (!write_data_ || !v) return "";
    const std::string rel = std::string(kViewerDataDir) + "/" + std::to_string(group_.index) + "-" +
                            std::to_string(item) + ".js";
    std::string key = url_path(rel);  // the script finds the data by the file's URL
    json d = {{"width", v->width},
              {"height", v->height},
              {"channels", v->channels},
              {"v", base64_floats(v->data)}};
    if (sigma && sigma->width == v->width && sigma->height == v->height)
      d["sigma"] = base64_floats(sigma->data), d["sigma_channels"] = sigma->channels;
    if (measured && measured->width == v->width && measured->height == v->height) {
      std::vector<unsigned char> bytes(measured->pixel_count());
      for (size_t p = 0; p < bytes.size(); ++p)
        bytes[p] = measured->data[p * static_cast<size_t>(measured->channels)] > 0.5f ? 1 : 0;
      d["measured"] = base64(bytes.data(), bytes.size());
    }
    core::make_own_folder(out_dir_.string(), kViewerDataDir);
    core::write_file_atomically((out_dir_ / rel).string(),
                                "sbViewerData(" + json(key).dump() + "," + d.dump() + ");\n");
    return key;
  }

  static std::optional<std::string> mask(const record::ImagesRecord& im, const char* region) {
    const auto it = im.masks.find(region);
    if (it == im.masks.end()) return std::nullopt;
    return it->second;
  }

  json reference_item(const JobRecord& r, size_t item) const {
    const auto& im = r.images;
    return {{"label", "reference"},
            {"status", "reference"},
            {"shaded", url(im.reference_shaded)},
            {"error", ""},
            {"flip", ""},
            {"data", data_file(item, read_named_image(run_dir_, im.reference_visibility),
                               read_named_image(run_dir_, im.reference_std_error),
                               read_named_image(run_dir_, mask(im, "all")))}};
  }

  json job_item(const JobRecord& r, size_t item) const {
    const auto& im = r.images;
    return {{"label", r.technique_variant},
            {"status", to_string(r.status)},
            {"shaded", url(im.shaded)},
            {"error", url(im.error_heatmap)},
            {"flip", url(im.flip_shaded)},
            {"data", data_file(item, read_named_image(run_dir_, im.visibility), std::nullopt)}};
  }

  std::string render(const json& config) const {
    const std::string text = json_for_script(config.dump());
    const std::string id = "viewer-" + std::to_string(group_.index);
    std::string out = "<section class=\"viewer\" id=\"" + id +
                      "\" tabindex=\"0\" data-state=\"loading\" aria-label=\"Compare images: " +
                      html_escape(group_.title) + "\">\n";
    out += "<script type=\"application/json\" class=\"viewer-config\">" + text + "</script>\n";
    out += "<div class=\"viewer-bar viewer-items\">";
    const auto& items = config["items"];
    for (size_t i = 0; i < items.size(); ++i) {
      out += "<button type=\"button\" data-item=\"" + std::to_string(i) + "\">";
      if (i < 9) out += "<kbd>" + std::to_string(i + 1) + "</kbd> ";
      out += html_escape(items[i]["label"].get<std::string>()) + "</button>";
    }
    out += "</div>\n<div class=\"viewer-bar\"><span class=\"viewer-modes\">";
    for (const auto& [mode, label, key] :
         {std::tuple<const char*, const char*, const char*>{"shaded", "shaded", "s"},
          {"v", "V", "v"},
          {"error", "error", "e"},
          {"flip", "FLIP", "f"}})
      out += std::string("<button type=\"button\" data-mode=\"") + mode + "\"><kbd>" + key +
             "</kbd> " + label + "</button>";
    out +=
        "</span><label>exposure <input type=\"range\" class=\"viewer-ev\" min=\"-8\" max=\"8\" "
        "step=\"0.5\" value=\"0\"> <output class=\"viewer-ev-out\">+0 EV</output></label>"
        "<label><input type=\"checkbox\" class=\"viewer-split-on\"> split with</label> "
        "<select class=\"viewer-b\" aria-label=\"image right of the split\">";
    for (size_t i = 0; i < items.size(); ++i)
      out += "<option value=\"" + std::to_string(i) + "\">" +
             html_escape(items[i]["label"].get<std::string>()) + "</option>";
    out +=
        "</select><span class=\"viewer-zoom\">fit</span><button type=\"button\" "
        "class=\"viewer-fit\"><kbd>0</kbd> fit</button></div>\n"
        "<div class=\"viewer-stage\"><canvas class=\"viewer-canvas\"></canvas></div>\n"
        "<input type=\"range\" class=\"viewer-split\" min=\"0\" max=\"1000\" value=\"500\" "
        "aria-label=\"split position\" hidden>\n"
        "<div class=\"viewer-readout\" aria-live=\"polite\">Point at a pixel to read its "
        "values.</div>\n"
        "<p class=\"note\">Keys (click the viewer first): 1&ndash;9 or &larr; &rarr; flip "
        "between images; s, v, e, f: shaded, V, error, FLIP; c: split against the image chosen "
        "right of it, b: take the one shown as that image; [ ]: exposure; + &minus; 0 or the "
        "wheel: zoom (drag to pan). V and error are drawn from the EXRs, with the exposure: V "
        "as grey (linear, 1 = white; NaN magenta), error in the heat map's colours at its full "
        "scale, over the measured pixels as error.png; the reference's error view is its "
        "standard error &sigma;.</p>\n</section>\n";
    return out;
  }

  const ViewerGroup& group_;
  fs::path run_dir_, out_dir_, run_from_out_;
  bool write_data_;
};

}  // namespace

std::string image_viewer(const ViewerGroup& group, const fs::path& run_dir, const fs::path& out_dir,
                         const fs::path& run_from_out, bool write_data) {
  return ViewerWriter(group, run_dir, out_dir, run_from_out, write_data).markup();
}

}  // namespace sb::results
