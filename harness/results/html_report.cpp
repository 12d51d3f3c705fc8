#include "results/html_report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "core/atomic_file.h"
#include "core/format_number.h"
#include "core/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "results/mixed_hosts.h"
#include "results/report_columns.h"
#include "results/stability_table.h"
#include "results/store.h"

namespace sb::results {

using core::format_number;
using core::ImageF;
using core::write_file_atomically;
using record::JobRecord;
using record::JobStatus;
using record::ReferenceRecord;

namespace {

namespace fs = std::filesystem;

// The page's style and script: inline, so that the report works offline.
constexpr const char* kStyle = R"css(
:root{--fg:#1d2330;--muted:#5d6677;--line:#d8dde6;--bg:#f5f6f8;--card:#fff}
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 system-ui,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;color:var(--fg);background:var(--bg)}
header{background:#1d2330;color:#fff;padding:18px 28px 14px}
header h1{margin:0 0 6px;font-size:22px;font-weight:600}
header p{margin:2px 0;color:#c8d0de}
header a{color:#9dc2ff}
nav{margin-top:10px;font-size:13px}
nav a{margin-right:14px;white-space:nowrap}
main{padding:4px 28px 40px}
h2{font-size:19px;margin:26px 0 10px;padding-bottom:4px;border-bottom:2px solid var(--line)}
h3{font-size:15px;margin:22px 0 8px;font-weight:600}
h3 a{font-size:12px;font-weight:400;margin-left:8px}
.note{color:var(--muted);margin:4px 0 10px}
.banner{background:#fde5e5;color:#8c1414;border:1px solid #f0b4b4;padding:8px 12px;border-radius:6px;margin:14px 0 0}
.mono,.name{font-family:ui-monospace,"DejaVu Sans Mono",monospace;font-size:12.5px}
.table-wrap{overflow-x:auto}
table{border-collapse:collapse;background:var(--card);border:1px solid var(--line);font-size:12.5px}
th,td{padding:4px 7px;border-bottom:1px solid var(--line);text-align:left;white-space:nowrap}
th{background:#eaeef5;cursor:pointer;user-select:none}
th:hover{background:#dde4ef}
th[aria-sort=ascending]::after{content:" \25B2";font-size:9px}
th[aria-sort=descending]::after{content:" \25BC";font-size:9px}
td.num,th.num{text-align:right;font-variant-numeric:tabular-nums}
tbody tr:nth-child(even){background:#f9fafb}
tbody tr:hover{background:#eef3fb}
td.reason{white-space:normal;max-width:460px;color:var(--muted)}
dl.facts{margin:0;font-size:12px;display:grid;grid-template-columns:auto 1fr;gap:2px 10px;align-content:start}
dl.facts dt{color:var(--muted)}
dl.facts dd{margin:0;font-variant-numeric:tabular-nums;word-break:break-all}
.status{display:inline-block;padding:0 7px;border-radius:9px;font-size:12px;font-weight:600}
.s-ok{background:#e0f3e5;color:#16672d}
.s-skipped{background:#eaecf0;color:#566074}
.s-failed,.s-other{background:#fde3e3;color:#a01c1c}
.v-ok{background:#e0f3e5;color:#16672d}
.v-degraded{background:#fdf0d5;color:#8a5a00}
.v-broken,.v-failed{background:#fde3e3;color:#a01c1c}
.v-skipped{background:#eaecf0;color:#566074}
td.stab{white-space:normal;min-width:160px;vertical-align:top}
.charts{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:16px}
.chart,.card{margin:0;background:var(--card);border:1px solid var(--line);border-radius:6px;padding:10px}
.chart img{width:100%;height:auto;display:block}
.chart figcaption{margin-top:6px;font-weight:600;font-size:13px}
.chart figcaption a{font-weight:400;font-size:12px;margin-left:8px}
.legend{display:flex;align-items:center;gap:12px;margin:4px 0 12px;flex-wrap:wrap}
.legend .bar{width:360px}
.legend .bar img{width:100%;height:14px;display:block;border:1px solid #9aa3b2}
.ticks{display:flex;justify-content:space-between;font-size:12px;color:var(--muted);font-variant-numeric:tabular-nums}
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(480px,1fr));gap:14px;align-items:start}
.card.ref{border-color:#98b0dc;box-shadow:inset 3px 0 0 #5b82c9}
.card-head{display:flex;flex-wrap:wrap;align-items:baseline;gap:4px 10px;margin-bottom:8px}
.name{font-weight:600;word-break:break-all}
.nums{color:var(--muted);font-size:12px;font-variant-numeric:tabular-nums}
.pair{display:grid;grid-template-columns:1fr 1fr;gap:8px}
.pair img{width:100%;height:auto;display:block;background:#e9ebef}
.cap{font-size:12px;color:var(--muted);margin-top:2px}
.placeholder{display:flex;align-items:center;justify-content:center;aspect-ratio:4/3;background:#f1f2f5;border:1px dashed #c5cbd6;color:var(--muted);font-size:12px;text-align:center;padding:6px}
.reason-text{margin:8px 0 0;color:#7a2020;font-size:12.5px;white-space:pre-wrap;word-break:break-word}
.reason-text.s-skipped{color:var(--muted)}
img.missing{outline:3px solid #d22;min-height:40px}
)css";

constexpr const char* kScript = R"js(
(function () {
  'use strict';
  // Sorting: numbers (inf and -inf included) numerically, the rest as text
  // with digits compared as numbers; empty cells last in either direction.
  function key(cell) {
    var t = cell.textContent.trim();
    if (t === '') return null;
    if (t === 'inf') return Infinity;
    if (t === '-inf') return -Infinity;
    var n = Number(t);
    return isNaN(n) ? t : n;
  }
  function compare(a, b) {
    var an = typeof a === 'number', bn = typeof b === 'number';
    if (an && bn) return a < b ? -1 : a > b ? 1 : 0;
    if (an !== bn) return an ? -1 : 1;
    return a.localeCompare(b, undefined, {numeric: true});
  }
  document.querySelectorAll('table.sortable').forEach(function (table) {
    var heads = Array.prototype.slice.call(table.tHead.rows[0].cells);
    heads.forEach(function (th, col) {
      th.tabIndex = 0;
      th.title = 'Sort by ' + th.textContent;
      function sort() {
        var asc = th.getAttribute('aria-sort') !== 'ascending';
        heads.forEach(function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', asc ? 'ascending' : 'descending');
        var body = table.tBodies[0];
        var rows = Array.prototype.map.call(body.rows, function (r, i) {
          return {row: r, i: i, k: key(r.cells[col])};
        });
        rows.sort(function (a, b) {
          if (a.k === null || b.k === null) {
            return (a.k === null) - (b.k === null) || a.i - b.i;
          }
          var c = compare(a.k, b.k);
          return (asc ? c : -c) || a.i - b.i;
        });
        rows.forEach(function (x) { body.appendChild(x.row); });
      }
      th.addEventListener('click', sort);
      th.addEventListener('keydown', function (e) {
        if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); sort(); }
      });
    });
  });
  // After every image has loaded or failed: record which did not load.
  window.addEventListener('load', function () {
    var missing = [];
    document.querySelectorAll('img').forEach(function (img) {
      if (img.complete && img.naturalWidth > 0) return;
      var src = img.getAttribute('src');
      missing.push(src);
      img.classList.add('missing');
      console.error('missing image: ' + src);
    });
    document.body.dataset.imagesOk = missing.length === 0 ? 'true' : 'false';
    document.body.dataset.missing = missing.join(' ');
    if (missing.length > 0) {
      var note = document.getElementById('image-status');
      note.textContent = missing.length + ' image(s) did not load: ' + missing.join(', ');
      note.hidden = false;
    }
  });
})();
)js";

// A relative URL for a file path: every byte but unreserved characters and
// '/', '=', '+', ',' percent-encoded (':' too, so no segment reads as a scheme).
std::string url_path(const std::string& path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : path) {
    const unsigned char c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       (c != 0 && std::strchr("-._~/=+,", c) != nullptr);
    if (plain) {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

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
       const std::string& title)
      : records_(records),
        run_dir_(run_dir),
        out_dir_(out_dir),
        run_from_out_(run_from_out),
        charts_(charts),
        title_(title) {
    for (size_t i = 0; i < records.size(); ++i) {
      const std::string key = records[i].scene_variant + " @ " + records[i].resolution;
      if (!group_index_.count(key)) {
        group_index_[key] = groups_.size();
        groups_.push_back({key, {}});
      }
      groups_[group_index_[key]].rows.push_back(i);
    }
  }

  std::string render() {
    out_ = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    out_ += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    out_ += "<title>" + html_escape(title_) + "</title>\n<style>" + kStyle + "</style>\n</head>\n";
    out_ += "<body data-images-ok=\"pending\" data-missing=\"\">\n";
    header();
    out_ += "<main>\n";
    summary();
    stability();
    charts();
    images();
    out_ += "</main>\n<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";
    return out_;
  }

 private:
  struct Group {
    std::string key;
    std::vector<size_t> rows;  // indices into records_
  };

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
    if (const auto hosts = distinct_hosts(records_); hosts.size() > 1) {
      out_ += "<p class=\"warning\"><strong>Mixed hosts:</strong> these jobs were timed on " +
              std::to_string(hosts.size()) +
              " hosts or GL renderers (merged with <span class=\"mono\">--allow-mixed-hosts</span>)"
              "; compare frame times only between jobs of one host:</p>\n<ul>\n";
      for (const auto& h : hosts) out_ += "<li>" + html_escape(h) + "</li>\n";
      out_ += "</ul>\n";
    }
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
    out_ += "penumbra only). Click a column header to sort.</p>\n";
    // Scene and resolution are the group's.
    const std::vector<const ReportColumn*> shown = group_table_columns(records_);
    for (size_t g = 0; g < groups_.size(); ++g) {
      out_ += "<h3 id=\"summary-" + std::to_string(g) + "\">" + html_escape(groups_[g].key) +
              "<a href=\"#images-" + std::to_string(g) + "\">images</a></h3>\n";
      out_ += "<div class=\"table-wrap\"><table class=\"sortable\">\n<thead><tr>";
      for (const ReportColumn* c : shown)
        out_ += std::string("<th") + (c->numeric() ? " class=\"num\"" : "") + ">" +
                html_escape(c->header) + "</th>";
      out_ += "</tr></thead>\n<tbody>\n";
      for (size_t r : groups_[g].rows) {
        out_ += "<tr>";
        for (const ReportColumn* c : shown) {
          const std::string name = c->name;
          if (name == "status")
            out_ += "<td>" + status_badge(records_[r].status) + "</td>";
          else if (name == "technique")
            out_ += "<td class=\"name\">" + html_escape(c->cell(records_[r])) + "</td>";
          else if (name == "reason")
            out_ += "<td class=\"reason\">" + html_escape(c->cell(records_[r])) + "</td>";
          else
            out_ += "<td class=\"num\">" + html_escape(c->cell(records_[r])) + "</td>";
        }
        out_ += "</tr>\n";
      }
      out_ += "</tbody>\n</table></div>\n";
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
      for (size_t i : groups_[g].rows) {
        const JobRecord& r = records_[i];
        if (r.images.error_heatmap_full_scale) scales.insert(*r.images.error_heatmap_full_scale);
        if (!ref && r.images.reference_shaded) ref = &r;
      }
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
      for (size_t i : groups_[g].rows) card(i, scales.size() > 1);
      out_ += "</div>\n";
    }
    out_ += "</section>\n";
  }

  void card(size_t i, bool label_scale) {
    const JobRecord& r = records_[i];
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
    out_ += "<figure class=\"card\" id=\"job-" + std::to_string(i) +
            "\"><div class=\"card-head\"><span class=\"name\">" + html_escape(name) + "</span>" +
            status_badge(r.status) + "<span class=\"nums\">" + nums + "</span></div>";
    if (r.images.shaded || r.images.error_heatmap)
      out_ += "<div class=\"pair\">" + image(r, r.images.shaded, name + ", shaded", "shaded") +
              image(r, r.images.error_heatmap, name + ", error heat map", heat_caption) + "</div>";
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
  std::vector<Group> groups_;
  std::map<std::string, size_t> group_index_;
  std::string out_;
};

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void write_html_report(const std::vector<JobRecord>& records, const std::string& run_dir,
                       const std::string& out_dir, const std::vector<ReportChart>& charts,
                       const std::string& title) {
  fs::create_directories(out_dir);
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir));
  fs::path run_from_out = fs::weakly_canonical(fs::absolute(run_dir)).lexically_relative(out);
  if (run_from_out.empty()) run_from_out = fs::weakly_canonical(fs::absolute(run_dir));
  write_legend(fs::path(out_dir) / kHeatmapLegendFile);
  write_file_atomically((fs::path(out_dir) / "index.html").string(),
                        Page(records, run_dir, out, run_from_out, charts, title).render());
}

}  // namespace sb::results
