#include "results/html_report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <string_view>
#include <tuple>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "results/banner.h"
#include "results/html_page.h"
#include "results/image_viewer.h"
#include "results/noisy_jobs.h"
#include "results/ranking_tables.h"
#include "results/record_groups.h"
#include "results/report_columns.h"
#include "results/sessions.h"
#include "results/stability_table.h"

namespace sb::results {

using core::format_number;
using core::ImageF;
using core::write_file_atomically;
using record::JobRecord;
using record::JobStatus;
using record::ReferenceRecord;

namespace {

namespace fs = std::filesystem;

std::string fmt_g(double v, const char* format = "%g") { return format_number(format, v); }

std::string status_class(JobStatus status) { return std::string("s-") + to_string(status); }

std::string status_badge(JobStatus status) {
  return "<span class=\"status " + status_class(status) + "\">" + to_string(status) + "</span>";
}

// The heat-map ramp as an image, through the very function the heat maps use.
void write_legend(const fs::path& path) {
  constexpr int kWidth = 512, kHeight = 16;
  ImageF img(kWidth, kHeight, 3);
  for (int x = 0; x < kWidth; ++x) {
    float rgb[3];
    metrics::heatmap_colour(static_cast<float>(x) / (kWidth - 1), rgb);
    for (int y = 0; y < kHeight; ++y)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = rgb[c];
  }
  metrics::io::write_png(path.string(), img);
}

class Page {
 public:
  Page(const std::vector<JobRecord>& records, const fs::path& run_dir, const fs::path& out_dir,
       const fs::path& run_from_out, const std::vector<ReportChart>& charts,
       const std::string& title, bool viewer_data)
      : records_(records),
        run_dir_(run_dir),
        out_dir_(out_dir),
        run_from_out_(run_from_out),
        charts_(charts),
        title_(title),
        viewer_data_(viewer_data),
        groups_(by_scene_and_resolution(records)) {}

  std::string render() {
    out_ = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    out_ += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    out_ += "<title>" + html_escape(title_) + "</title>\n<style>" + page_style() +
            image_viewer_style() + "</style>\n</head>\n";
    out_ += "<body data-images-ok=\"pending\" data-missing=\"\">\n";
    header();
    out_ += "<main>\n";
    summary();
    stability();
    charts();
    images();
    out_ += "</main>\n<script>" + std::string(page_script()) + image_viewer_script() +
            "</script>\n</body>\n</html>\n";
    return out_;
  }

 private:
  // A path relative to the run directory, as a URL relative to the report.
  std::string run_link(const std::string& rel) const {
    return html_escape(url_path((run_from_out_ / rel).lexically_normal().generic_string()));
  }

  void header() {
    out_ += "<header>\n<h1>" + html_escape(title_) + "</h1>\n";
    if (!records_.empty()) {
      const JobRecord& r0 = records_.front();
      out_ += "<p>Backend <span class=\"mono\">" + html_escape(r0.backend) +
              "</span>, renderer <span class=\"mono\">" + html_escape(r0.gl_renderer) +
              "</span>, timing source <span class=\"mono\">" + html_escape(r0.timing_source) +
              "</span>. Reference: " + reference_method(r0) + ".</p>\n";
    }
    out_ += html_banners(report_banners(records_));  // mixed hosts or sessions
    // ok, skipped, failed, then any other status, each with its count.
    std::string tally;
    for (const JobStatus status : {JobStatus::Ok, JobStatus::Skipped, JobStatus::Failed}) {
      const auto n = std::count_if(records_.begin(), records_.end(),
                                   [&](const JobRecord& r) { return r.status == status; });
      if (n > 0) tally += (tally.empty() ? "" : ", ") + std::to_string(n) + " " + to_string(status);
    }
    out_ += "<p>" + std::to_string(records_.size()) + " jobs" +
            (tally.empty() ? "" : ": " + tally) + ". Run directory <a href=\"" + run_link(".") +
            "/\">" + html_escape(run_dir_.generic_string()) + "</a>";
    for (const char* file : {"results.jsonl", "results.csv", "summary.md"})
      if (fs::exists(run_dir_ / file))
        out_ += std::string(" &middot; <a href=\"") + run_link(file) + "\">" + file + "</a>";
    out_ += ".</p>\n<nav><a href=\"#summary\">Summary</a>";
    if (stability_table(records_)) out_ += "<a href=\"#stability\">Stability</a>";
    out_ += "<a href=\"#charts\">Charts</a>";
    out_ += "<a href=\"#images\">Images</a>";
    for (size_t g = 0; g < groups_.size(); ++g)
      out_ +=
          "<a href=\"#images-" + std::to_string(g) + "\">" + html_escape(groups_[g].key) + "</a>";
    out_ += "</nav>\n<p id=\"image-status\" class=\"banner\" hidden></p>\n</header>\n";
  }

  void summary() {
    out_ += "<section id=\"summary\">\n<h2>Summary</h2>\n<p class=\"note\">Times are medians in ";
    out_ += "milliseconds; error figures are on the visibility buffer over the geometry region ";
    out_ += "(surface pixels outside attached shadow: no sky), except penumbra_rmse (reference ";
    out_ += "penumbra only), terminator_rmse (the pixels whose tangent plane cuts the light, ";
    out_ += "which no other figure holds) and flip (the shaded image's FLIP over every pixel, as ";
    out_ += "NVIDIA's tool prints it). Click a column header to sort.</p>\n";
    // Scene and resolution are the group's.
    const Sessions sessions(records_);  // a column of their letters when mixed
    const std::vector<const ReportColumn*> shown = sessions.marked(group_table_columns(records_));
    for (size_t g = 0; g < groups_.size(); ++g) {
      out_ += "<h3 id=\"summary-" + std::to_string(g) + "\">" + html_escape(groups_[g].key) +
              "<a href=\"#images-" + std::to_string(g) + "\">images</a></h3>\n";
      out_ += "<div class=\"table-wrap\"><table class=\"sortable\">\n<thead><tr>";
      for (const ReportColumn* c : shown)
        out_ += std::string("<th") + (c->numeric() ? " class=\"num\"" : "") + ">" +
                html_escape(c->header) + "</th>";
      out_ += "</tr></thead>\n<tbody>\n";
      for (const JobRecord* r : groups_[g].records) {
        out_ += "<tr>";
        for (const ReportColumn* c : shown) {
          const std::string name = c->name;
          if (name == "status")
            out_ += "<td>" + status_badge(r->status) + "</td>";
          else if (name == "technique")
            out_ += "<td class=\"name\">" + html_escape(c->cell(*r)) + "</td>";
          else if (name == "reason")
            out_ += "<td class=\"reason\">" + html_escape(c->cell(*r)) + "</td>";
          else
            out_ += "<td class=\"num\">" + html_escape(c->cell(*r)) + "</td>";
        }
        out_ += "</tr>\n";
      }
      out_ += "</tbody>\n</table></div>\n";
      if (const std::string legend = noisy_legend(groups_[g].records); !legend.empty())
        out_ += std::string("<p class=\"note noisy\">") + kNoisyMark + " " + html_escape(legend) +
                "</p>\n";
      out_ += ranking_html(groups_[g].records);
    }
    out_ += "</section>\n";
  }

  // A chart file as a URL relative to the report: paths are relative to
  // out_dir, but an absolute one, or one relative to the working directory
  // (as write_charts returns them), is made relative to out_dir.
  std::string chart_link(const std::string& path) const {
    fs::path p(path);
    if (p.is_absolute() || (!fs::exists(out_dir_ / p) && fs::exists(p)))
      p = fs::weakly_canonical(fs::absolute(p)).lexically_relative(out_dir_);
    return html_escape(url_path(p.generic_string()));
  }

  // Technique × case, each cell its verdict and figures, linked to the job's
  // images below (results/stability_table.h).
  void stability() {
    const auto table = stability_table(records_);
    if (!table) return;
    out_ +=
        "<section id=\"stability\">\n<h2>Stability</h2>\n<p class=\"note\">ok, degraded "
        "(RMSE over the case's threshold, flicker over the reference's by the set factor, "
        "or a stiff parameter) or broken (V not finite or outside [0, 1]); docs/"
        "stability.md. A cell links to the job's images.</p>\n";
    out_ += "<div class=\"table-wrap\"><table>\n<thead><tr><th>technique</th>";
    for (const auto& c : table->cases) out_ += "<th>" + html_escape(c) + "</th>";
    out_ += "</tr></thead>\n<tbody>\n";
    for (size_t t = 0; t < table->techniques.size(); ++t) {
      out_ += "<tr><td class=\"name\">" + html_escape(table->techniques[t]) + "</td>";
      for (const JobRecord* r : table->cells[t]) {
        if (r == nullptr) {
          out_ += "<td></td>";
          continue;
        }
        const StabilityCell cell = stability_cell(*r);
        const auto index = size_t(r - records_.data());
        out_ += std::string("<td class=\"stab\"><a href=\"#job-") + std::to_string(index) +
                "\"><span class=\"status v-" + to_string(cell.verdict) + "\">" +
                to_string(cell.verdict) + "</span></a> <span class=\"nums\">" +
                html_escape(cell.figure) + "</span></td>";
      }
      out_ += "</tr>\n";
    }
    out_ += "</tbody></table></div>\n</section>\n";
  }

  void charts() {
    out_ += "<section id=\"charts\">\n<h2>Charts</h2>\n";
    if (charts_.empty()) out_ += "<p class=\"note\">No charts.</p>\n";
    out_ += "<div class=\"charts\">\n";
    for (const auto& c : charts_) {
      const std::string svg = c.svg.empty() ? "" : chart_link(c.svg);
      const std::string png = c.png.empty() ? "" : chart_link(c.png);
      out_ += "<figure class=\"chart\"><a href=\"" + (png.empty() ? svg : png) + "\"><img src=\"" +
              (svg.empty() ? png : svg) + "\" alt=\"" + html_escape(c.title) +
              "\"></a><figcaption>" + html_escape(c.title);
      if (!svg.empty()) out_ += "<a href=\"" + svg + "\">SVG</a>";
      if (!png.empty()) out_ += "<a href=\"" + png + "\">PNG</a>";
      out_ += "</figcaption></figure>\n";
    }
    out_ += "</div>\n</section>\n";
  }

  // One image of a record, linked to itself, with a caption; a placeholder
  // when the record names none.
  std::string image(const JobRecord& r, const std::optional<std::string>& path,
                    const std::string& alt, const std::string& caption) const {
    if (!path)
      return "<div><div class=\"placeholder\">no " + html_escape(caption) + " image</div></div>";
    const std::string href = run_link(*path);
    std::string size;
    if (r.width > 0 && r.height > 0)
      size =
          " width=\"" + std::to_string(r.width) + "\" height=\"" + std::to_string(r.height) + "\"";
    return "<div><a href=\"" + href + "\"><img src=\"" + href + "\" alt=\"" + html_escape(alt) +
           "\"" + size + "></a><div class=\"cap\">" + html_escape(caption) + "</div></div>";
  }

  void legend(double full_scale) {
    out_ +=
        "<div class=\"legend\"><span>Error heat map |V &minus; V<sub>ref</sub>| (max over "
        "channels):</span><div class=\"bar\"><img src=\"" +
        html_escape(url_path(kHeatmapLegendFile)) +
        "\" alt=\"heat map colour scale\"><div class=\"ticks\">";
    for (int i = 0; i <= 4; ++i)
      out_ +=
          std::string("<span>") + (i == 4 ? "&ge; " : "") + fmt_g(full_scale * i / 4) + "</span>";
    out_ += "</div></div><span class=\"note\">NaN/Inf shown as full scale</span></div>\n";
  }

  // What the reference is, beside its image: the record's "reference" fields.
  static std::string reference_facts(const ReferenceRecord& ref) {
    const std::pair<const char*, std::string> facts[] = {
        {"seed", std::to_string(ref.seed)},
        {"mean std error", fmt_g(ref.mean_std_error, "%.4g")},
        {"penumbra mean std error", fmt_g(ref.penumbra_mean_std_error, "%.4g")},
        {"penumbra pixels", std::to_string(ref.penumbra_pixels)},
        {"attached-shadow pixels", std::to_string(ref.attached_shadow_pixels)},
        {"from cache", ref.from_cache ? "true" : "false"}};
    std::string out = "<dl class=\"facts\">";
    for (const auto& [label, text] : facts)
      out += "<dt>" + std::string(label) + "</dt><dd>" + html_escape(text) + "</dd>";
    return out + "</dl>";
  }

  // The record's reference, as the tables say it ("" without one); and its
  // second reference, if it has one.
  static std::string reference_method(const JobRecord& r) {
    if (!r.reference) return "";
    std::string out = html_escape(reference_label(*r.reference));
    if (r.second_reference)
      out += "; second reference (the second_ columns): " +
             html_escape(reference_label(r.second_reference->reference));
    return out;
  }

  void images() {
    out_ += "<section id=\"images\">\n<h2>Images</h2>\n";
    for (size_t g = 0; g < groups_.size(); ++g) {
      out_ += "<h3 id=\"images-" + std::to_string(g) + "\">" + html_escape(groups_[g].key) +
              "<a href=\"#summary-" + std::to_string(g) + "\">table</a></h3>\n";
      std::set<double> scales;
      const JobRecord* ref = nullptr;
      for (const JobRecord* r : groups_[g].records) {
        if (r->images.error_heatmap_full_scale) scales.insert(*r->images.error_heatmap_full_scale);
        if (!ref && r->images.reference_shaded) ref = r;
      }
      const ViewerGroup viewer{static_cast<int>(g), groups_[g].key, groups_[g].records};
      out_ += image_viewer(viewer, run_dir_, out_dir_, run_from_out_, viewer_data_);
      for (double s : scales) legend(s);
      out_ += "<div class=\"grid\">\n";
      if (ref) {
        out_ +=
            "<figure class=\"card ref\"><div class=\"card-head\"><span class=\"name\">"
            "reference</span><span class=\"nums\">" +
            reference_method(*ref) + "</span></div><div class=\"pair\">" +
            image(*ref, ref->images.reference_shaded, "reference, shaded", "shaded") +
            (ref->reference ? reference_facts(*ref->reference) : "") + "</div></figure>\n";
      }
      for (const JobRecord* r : groups_[g].records) card(*r, scales.size() > 1);
      out_ += "</div>\n";
    }
    out_ += "</section>\n";
  }

  void card(const JobRecord& r, bool label_scale) {
    const std::string& name = r.technique_variant;
    std::string nums;
    for (const auto& [column, label, unit] :
         {std::tuple<const char*, const char*, const char*>{"frame_ms", "frame ", " ms"},
          {"rmse", "RMSE ", ""},
          {"penumbra_rmse", "penumbra RMSE ", ""}}) {
      const std::string v = report_column(column).cell(r);
      if (v.empty()) continue;
      nums += (nums.empty() ? "" : " &middot; ") + std::string(label) + html_escape(v) + unit;
    }
    std::string heat_caption = "error heat map";
    if (label_scale && r.images.error_heatmap_full_scale)
      heat_caption += ", full scale " + fmt_g(*r.images.error_heatmap_full_scale);
    // The job's place in the run, as the stability table links to it.
    out_ += "<figure class=\"card\" id=\"job-" + std::to_string(&r - records_.data()) +
            "\"><div class=\"card-head\"><span class=\"name\">" + html_escape(name) + "</span>" +
            status_badge(r.status) + "<span class=\"nums\">" + nums + "</span></div>";
    if (r.images.shaded || r.images.error_heatmap)
      out_ += "<div class=\"pair\">" + image(r, r.images.shaded, name + ", shaded", "shaded") +
              image(r, r.images.error_heatmap, name + ", error heat map", heat_caption) + "</div>";
    if (r.images.invalid)
      out_ += "<div class=\"pair\">" +
              image(r, r.images.invalid, name + ", invalid pixels",
                    "V's invalid pixels: red NaN/Inf, blue below 0, yellow above 1") +
              "</div>";
    const std::string reason = r.reason.value_or("");
    if (r.status != JobStatus::Ok || !reason.empty())
      out_ += "<p class=\"reason-text " + status_class(r.status) + "\">" + to_string(r.status) +
              (reason.empty() ? "" : ": " + html_escape(reason)) + "</p>";
    out_ += "</figure>\n";
  }

  const std::vector<JobRecord>& records_;
  fs::path run_dir_;
  fs::path out_dir_;  // canonical
  fs::path run_from_out_;
  const std::vector<ReportChart>& charts_;
  std::string title_;
  bool viewer_data_;
  std::vector<RecordGroup> groups_;  // by scene and resolution
  std::string out_;
};

// A data file the viewer writes: "<n>-<m>.js" (image_viewer.cpp).
bool viewer_data_name(const std::string& name) {
  const size_t dash = name.find('-');
  const auto digits = [](std::string_view t) {
    return !t.empty() &&
           std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  return dash != std::string::npos && name.size() > 3 &&
         name.compare(name.size() - 3, 3, ".js") == 0 &&
         digits(std::string_view(name).substr(0, dash)) &&
         digits(std::string_view(name).substr(dash + 1, name.size() - 3 - dash - 1));
}

}  // namespace

void check_viewer_folder(const std::string& out_dir) {
  const fs::path viewer = fs::path(out_dir) / kViewerDataDir;
  const std::string why = "is not the report's: the report replaces " + viewer.string() +
                          " only when it holds the viewer's files (its marker " +
                          kViewerMarkerFile +
                          "), and keeps anything else; move it away or choose another --out";
  const fs::file_status folder = fs::symlink_status(viewer);
  if (folder.type() == fs::file_type::not_found) return;
  if (folder.type() != fs::file_type::directory) throw core::InputError(viewer.string(), "", why);
  if (fs::symlink_status(viewer / kViewerMarkerFile).type() == fs::file_type::regular) return;
  // A viewer folder written before the marker holds only data files.
  for (const fs::directory_entry& e : fs::directory_iterator(viewer))
    if (!e.is_regular_file() || e.is_symlink() || !viewer_data_name(e.path().filename().string()))
      throw core::InputError(e.path().string(), "", why);
}

void write_html_report(const std::vector<JobRecord>& records, const std::string& run_dir,
                       const std::string& out_dir, const std::vector<ReportChart>& charts,
                       const std::string& title, bool viewer_data) {
  fs::create_directories(out_dir);
  // The viewers' data files are this report's alone: none survives from an
  // earlier report of more groups or jobs. The folder goes only when it is
  // the report's own, and the new one is marked as such first.
  check_viewer_folder(out_dir);
  fs::remove_all(fs::path(out_dir) / kViewerDataDir);
  if (viewer_data) {
    fs::create_directories(fs::path(out_dir) / kViewerDataDir);
    write_file_atomically((fs::path(out_dir) / kViewerDataDir / kViewerMarkerFile).string(),
                          "Written by shadowbench report: this folder is replaced by the next "
                          "report into its folder.\n");
  }
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir));
  fs::path run_from_out = fs::weakly_canonical(fs::absolute(run_dir)).lexically_relative(out);
  if (run_from_out.empty()) run_from_out = fs::weakly_canonical(fs::absolute(run_dir));
  write_legend(fs::path(out_dir) / kHeatmapLegendFile);
  write_file_atomically(
      (fs::path(out_dir) / "index.html").string(),
      Page(records, run_dir, out, run_from_out, charts, title, viewer_data).render());
}

}  // namespace sb::results
