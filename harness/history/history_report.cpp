#include "history/history_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/folder_file.h"
#include "core/format_number.h"
#include "core/names.h"
#include "history/stored_text.h"
#include "record/figures.h"
#include "results/charts.h"
#include "results/html_page.h"
#include "store/results_store.h"

namespace sb::history {

using core::format_number;
using core::write_file_atomically;
using results::html_escape;
using results::url_path;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The report's own styles, after the shared sheet (results/html_page.h).
constexpr const char* kStyle = R"css(
svg.spark{display:block}
svg.spark polyline{fill:none;stroke:#3b6fc4;stroke-width:1.3}
svg.spark line.step{stroke:#d0342c;stroke-width:1.2}
svg.spark circle{fill:#3b6fc4}
td.steps{font-weight:600;color:#b02a22}
td.steps.none{font-weight:400;color:var(--muted)}
.up{color:#b02a22}.down{color:#16672d}
.thumbs{display:grid;grid-template-columns:repeat(4,minmax(120px,1fr));gap:8px;margin:6px 0 14px}
.thumbs figure{margin:0}.thumbs img{width:100%;height:auto;display:block;background:#e9ebef}
.thumbs figcaption{font-size:12px;color:var(--muted)}
figure.history-chart{max-width:960px}
)css";

std::string fmt(double v, const char* format = "%.4g") {
  return std::isnan(v) ? "" : format_number(format, v);
}

// A run's own noise of its time ("±3.1 %"), and "loaded" where the
// detector took the run as loaded.
std::string own_noise_cell(const SeriesHistory& s, std::size_t run) {
  if (run >= s.time_noise.size() || std::isnan(s.time_noise[run])) return "";
  const bool loaded = run < s.time_loaded.size() && s.time_loaded[run];
  return "\u00b1" + format_number("%.1f", 100 * s.time_noise[run]) + " %" +
         (loaded ? " <em>loaded</em>" : "");
}

std::string percent(double relative_change) {
  if (std::isinf(relative_change)) return relative_change > 0 ? "+inf" : "-inf";
  return format_number("%+.1f", 100.0 * relative_change) + " %";
}

// Text is cut by characters, never inside one (a commit may be "abcdefé-x").
std::string short_commit(const std::string& commit) { return utf8_prefix(commit, 10); }

// A quantity as a column heading: "frame / control", "frame ms", the metric path.
std::string quantity_label(const std::string& quantity) {
  if (const record::TimeSeries* t = record::find_time_series(quantity)) return t->heading;
  return quantity.substr(quantity.find('.') + 1);  // metrics.<path>
}

// The last value of a series, and the run it is from (-1 when none).
std::ptrdiff_t last_run_with_value(const std::vector<double>& v, std::size_t before) {
  for (std::size_t i = std::min(before, v.size()); i-- > 0;)
    if (!std::isnan(v[i])) return static_cast<std::ptrdiff_t>(i);
  return -1;
}

// A small inline SVG of one series: a line through the values (broken where
// a run has none), a red mark at each step, a dot on the latest value.
std::string sparkline(const std::vector<double>& v, const std::vector<ChangePoint>& steps) {
  constexpr double kW = 140, kH = 28, kPad = 3;
  double lo = INFINITY, hi = -INFINITY;
  for (double x : v)
    if (!std::isnan(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  std::string svg = "<svg class=\"spark\" width=\"" + fmt(kW) + "\" height=\"" + fmt(kH) +
                    "\" viewBox=\"0 0 " + fmt(kW) + " " + fmt(kH) + "\" role=\"img\">";
  if (!std::isfinite(lo)) return svg + "</svg>";
  const double n = static_cast<double>(std::max<std::size_t>(v.size(), 2) - 1);
  auto x_of = [&](std::size_t i) { return kPad + (kW - 2 * kPad) * static_cast<double>(i) / n; };
  auto y_of = [&](double y) {
    return hi > lo ? kH - kPad - (kH - 2 * kPad) * (y - lo) / (hi - lo) : kH / 2;
  };
  for (const ChangePoint& s : steps) {
    const std::string x = fmt(x_of(s.index) - 0.5 * (x_of(1) - x_of(0)), "%.1f");
    svg += "<line class=\"step\" x1=\"";
    svg += x;
    svg += "\" x2=\"";
    svg += x;
    svg += "\" y1=\"0\" y2=\"" + fmt(kH) + "\"/>";
  }
  std::string points;
  auto flush = [&] {
    if (!points.empty()) svg += "<polyline points=\"" + points + "\"/>";
    points.clear();
  };
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::isnan(v[i])) {
      flush();
      continue;
    }
    points += (points.empty() ? "" : " ") + fmt(x_of(i), "%.1f") + "," + fmt(y_of(v[i]), "%.1f");
  }
  flush();
  const std::ptrdiff_t last = last_run_with_value(v, v.size());
  svg += "<circle cx=\"" + fmt(x_of(static_cast<std::size_t>(last)), "%.1f") + "\" cy=\"" +
         fmt(y_of(v[static_cast<std::size_t>(last)]), "%.1f") + "\" r=\"2\"/>";
  return svg + "</svg>";
}

// The hosts of a history, numbered in order of first appearance.
class Hosts {
 public:
  explicit Hosts(const std::vector<SeriesHistory>& all) {
    for (std::size_t run = 0; !all.empty() && run < all.front().jobs.runs.size(); ++run)
      for (const SeriesHistory& s : all)
        if (s.jobs.runs[run].present) add(s.jobs.runs[run].host_fingerprint);
  }
  int number(const std::string& fingerprint) const { return number_.at(fingerprint); }
  std::string label(const std::string& fingerprint) const {
    const std::string short_fp = fingerprint.empty() ? "unknown" : utf8_prefix(fingerprint, 12);
    return "host " + std::to_string(number(fingerprint) + 1) + " (" + short_fp + ")";
  }
  const std::vector<std::string>& fingerprints() const { return order_; }

 private:
  void add(const std::string& fp) {
    if (number_.emplace(fp, static_cast<int>(order_.size())).second) order_.push_back(fp);
  }
  std::map<std::string, int> number_;
  std::vector<std::string> order_;
};

// A path to `target` relative to `from_dir`, as a URL ("" when the target is
// not on this machine).
std::string link_to(const fs::path& target, const fs::path& from_dir) {
  std::error_code ec;
  if (!fs::exists(target, ec)) return "";
  const fs::path rel =
      fs::weakly_canonical(target, ec).lexically_relative(fs::weakly_canonical(from_dir, ec));
  return html_escape(url_path(rel.empty() ? target.generic_string() : rel.generic_string()));
}

// Whether run_dir/rel is a regular file inside run_dir, reached without a
// symbolic link.
bool inside_folder(const std::string& run_dir, const std::string& rel) {
  try {
    return core::open_in_folder(run_dir, rel).has_value();
  } catch (const core::InputError&) {
    return false;
  }
}

std::string page_head(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
         html_escape(title) + "</title>\n<style>" + results::page_style() + kStyle +
         "</style>\n</head>\n<body>\n";
}

std::string page_end() {
  return "<p id=\"image-status\" class=\"banner\" hidden></p>\n</main>\n<script>" +
         std::string(results::page_script()) + "</script>\n</body>\n</html>\n";
}

class Site {
 public:
  Site(const HistoryDb& db, const fs::path& out, const HistoryReportOptions& options)
      : db_(db),
        out_(out),
        options_(options),
        runs_(db.runs()),
        series_(series_histories(db, options.quantities)),
        hosts_(series_) {}

  HistoryReport write() {
    // series/ is the tool's own folder in the site's: a symlink planted
    // there is refused, never written through.
    core::make_own_folder(out_.string(), "series", "history report: ");
    for (std::size_t i = 0; i < series_.size(); ++i) collect_steps(i);
    std::stable_sort(steps_.begin(), steps_.end(), [](const auto& a, const auto& b) {
      return a.run_order != b.run_order ? a.run_order > b.run_order : a.series < b.series;
    });
    std::vector<std::string> charts;
    for (std::size_t i = 0; i < series_.size(); ++i) charts.push_back(chart_data(i));
    results::draw_chart_data(charts);
    for (std::size_t i = 0; i < series_.size(); ++i)
      write_file_atomically((out_ / page(i)).string(), series_page(i));
    write_file_atomically((out_ / "index.html").string(), index_page());
    write_file_atomically((out_ / "steps.json").string(), store::json_text(steps_json(), 1) + "\n");

    HistoryReport report;
    report.index = (out_ / "index.html").string();
    report.runs = runs_.size();
    report.series = series_.size();
    report.hosts = hosts_.fingerprints().size();
    report.steps = steps_;
    std::sort(report.steps.begin(), report.steps.end(), [](const auto& a, const auto& b) {
      return a.run_order != b.run_order ? a.run_order < b.run_order : a.series < b.series;
    });
    return report;
  }

 private:
  const HistoryQuantities& q() const { return options_.quantities; }
  std::string page(std::size_t i) const {
    const SeriesJobs& j = series_[i].jobs;
    return "series/" + core::job_id(j.scene_variant, j.resolution, j.technique_variant) + ".html";
  }
  bool times_across_hosts() const {
    return hosts_.fingerprints().size() > 1 && q().time != "time.frame_ratio";
  }

  void collect_steps(std::size_t i) {
    const SeriesHistory& s = series_[i];
    auto add = [&](const std::string& quantity, const std::vector<ChangePoint>& found,
                   const std::vector<double>& values) {
      for (const ChangePoint& c : found) {
        ReportedStep r;
        r.series = s.jobs.series;
        r.quantity = quantity;
        r.commit = runs_[c.index].commit;
        const std::ptrdiff_t before = last_run_with_value(values, c.index);
        if (before >= 0) r.previous_commit = runs_[static_cast<std::size_t>(before)].commit;
        r.run_order = runs_[c.index].run_order;
        r.page = page(i);
        r.change = c;
        steps_.push_back(r);
      }
    };
    add(q().time, s.time_steps, s.time);
    add(q().error, s.error_steps, s.error);
  }

  // The chart's data for plot_charts.py (kind "history"): both panels against
  // run order, a marker per host, segment medians and steps.
  std::string chart_data(std::size_t i) const {
    const SeriesHistory& s = series_[i];
    const fs::path stem = out_ / fs::path(page(i)).replace_extension("");
    json ticks = json::array(), hosts = json::array(), host_labels = json::array();
    for (const HistoryRun& r : runs_) ticks.push_back(utf8_prefix(r.commit, 7));
    for (const SeriesJob& j : s.jobs.runs)
      hosts.push_back(j.present ? hosts_.number(j.host_fingerprint) : -1);
    for (const std::string& fp : hosts_.fingerprints()) host_labels.push_back(hosts_.label(fp));
    auto panel = [&](const std::string& quantity, const std::vector<double>& values,
                     const std::vector<ChangePoint>& steps) {
      json v = json::array(), step_at = json::array(), segments = json::array();
      for (double x : values) v.push_back(std::isnan(x) ? json(nullptr) : json(x));
      std::size_t from = 0;
      for (const ChangePoint& c : steps) {
        segments.push_back({{"from", from}, {"to", c.index}, {"level", c.before}});
        step_at.push_back(c.index);
        from = c.index;
      }
      const double last_level =
          steps.empty() ? std::nan("") : steps.back().after;  // no step: no segment line
      if (!steps.empty())
        segments.push_back({{"from", from}, {"to", values.size()}, {"level", last_level}});
      return json{{"ylabel", quantity_label(quantity)},
                  {"values", v},
                  {"steps", step_at},
                  {"segments", segments}};
    };
    json d = {{"kind", "history"},
              {"title", s.jobs.series},
              {"svg", stem.string() + ".svg"},
              {"png", stem.string() + ".png"},
              {"xlabel", "run (commit), oldest first"},
              {"ticks", ticks},
              {"hosts", hosts},
              {"host_labels", host_labels},
              {"panels",
               {panel(q().time, s.time, s.time_steps), panel(q().error, s.error, s.error_steps)}}};
    std::string file = stem.string() + ".json";
    write_file_atomically(file, store::json_text(d, 1) + "\n");
    return file;
  }

  std::string header(const std::string& title, const std::string& up) const {
    std::string h =
        "<header><h1>" + html_escape(title) + "</h1><p>" + std::to_string(runs_.size()) + " runs";
    if (!runs_.empty())
      h += ", commits <span class=\"mono\">" + html_escape(short_commit(runs_.front().commit)) +
           "</span> to <span class=\"mono\">" + html_escape(short_commit(runs_.back().commit)) +
           "</span>";
    h += ", " + std::to_string(hosts_.fingerprints().size()) +
         " host(s); from <span class=\"mono\">" + html_escape(db_.path()) +
         "</span></p><p>time: " + html_escape(quantity_label(q().time)) +
         "; error: " + html_escape(quantity_label(q().error)) + "</p>";
    if (!up.empty()) h += "<nav><a href=\"" + up + "\">all series</a></nav>";
    h += "</header>\n";
    if (times_across_hosts())
      h += "<p class=\"banner\">These times are in milliseconds on " +
           std::to_string(hosts_.fingerprints().size()) +
           " different hosts, which are not comparable: a step can be a change of host. "
           "The default, the frame time over the control's (--time ratio), is.</p>\n";
    return h + "<main>\n";
  }

  std::string step_row(const ReportedStep& r, const std::string& series_link) const {
    const ChangePoint& c = r.change;
    return "<tr><td class=\"num\">" + std::to_string(r.run_order) + "</td><td class=\"mono\">" +
           html_escape(short_commit(r.commit)) + "</td><td class=\"mono\">" +
           html_escape(short_commit(r.previous_commit)) + "</td><td class=\"name\">" + series_link +
           "</td><td>" + html_escape(quantity_label(r.quantity)) + "</td><td class=\"num\">" +
           fmt(c.before) + "</td><td class=\"num\">" + fmt(c.after) + "</td><td class=\"num " +
           (c.relative_change > 0 ? "up" : "down") + "\">" + percent(c.relative_change) +
           "</td><td class=\"num\">" + fmt(c.step_over_sigma, "%.1f") + "</td><td class=\"num\">" +
           std::to_string(c.runs_before) + "</td><td class=\"num\">" +
           std::to_string(c.runs_after) + "</td></tr>\n";
  }

  static std::string steps_table_head() {
    return "<div class=\"table-wrap\"><table class=\"sortable steps\"><thead><tr><th "
           "class=\"num\">run</th><th>commit</th><th>previous commit</th><th>series</th><th>"
           "quantity</th><th class=\"num\">before</th><th class=\"num\">after</th><th "
           "class=\"num\">change</th><th class=\"num\">step/&sigma;</th><th class=\"num\">runs "
           "before</th><th class=\"num\">runs after</th></tr></thead><tbody>\n";
  }

  std::string index_page() const {
    std::string h = page_head(options_.title) + header(options_.title, "");
    h += "<section id=\"steps\"><h2>Steps</h2>\n";
    if (steps_.empty()) {
      h += "<p class=\"note\">No step in any series.</p>\n";
    } else {
      h += "<p class=\"note\">Newest first. A step is reported once 3 runs stand at the new "
           "level; before and after are the medians of the runs on each side.</p>\n" +
           steps_table_head();
      for (const ReportedStep& r : steps_)
        h += step_row(r, "<a href=\"" + html_escape(url_path(r.page)) + "\">" +
                             html_escape(r.series) + "</a>");
      h += "</tbody></table></div>\n";
    }
    h += "</section>\n<section id=\"series\"><h2>Series</h2>\n"
         "<div class=\"table-wrap\"><table class=\"sortable\"><thead><tr><th>scene</th><th>"
         "resolution</th><th>technique</th><th class=\"num\">runs</th><th class=\"num\">" +
         html_escape(quantity_label(q().time)) +
         "</th><th>trend</th><th class=\"num\">steps</th>"
         "<th class=\"num\">" +
         html_escape(quantity_label(q().error)) +
         "</th><th>trend</th><th class=\"num\">steps</th></tr></thead><tbody>\n";
    for (std::size_t i = 0; i < series_.size(); ++i) {
      const SeriesHistory& s = series_[i];
      std::size_t with_value = 0;
      for (const SeriesJob& j : s.jobs.runs) with_value += j.present ? 1 : 0;
      auto latest = [](const std::vector<double>& v) {
        const std::ptrdiff_t at = last_run_with_value(v, v.size());
        return at < 0 ? std::string() : fmt(v[static_cast<std::size_t>(at)]);
      };
      auto steps_cell = [](const std::vector<ChangePoint>& found) {
        return found.empty() ? std::string("<td class=\"num steps none\">0</td>")
                             : "<td class=\"num steps\">" + std::to_string(found.size()) + "</td>";
      };
      h += "<tr data-series=\"" + html_escape(s.jobs.series) + "\"><td>" +
           html_escape(s.jobs.scene_variant) + "</td><td>" + html_escape(s.jobs.resolution) +
           "</td><td class=\"name\"><a href=\"" + html_escape(url_path(page(i))) + "\">" +
           html_escape(s.jobs.technique_variant) + "</a></td><td class=\"num\">" +
           std::to_string(with_value) + "</td><td class=\"num\">" + latest(s.time) + "</td><td>" +
           sparkline(s.time, s.time_steps) + "</td>" + steps_cell(s.time_steps) +
           "<td class=\"num\">" + latest(s.error) + "</td><td>" +
           sparkline(s.error, s.error_steps) + "</td>" + steps_cell(s.error_steps) + "</tr>\n";
    }
    h += "</tbody></table></div></section>\n" + runs_section(out_) + hosts_section();
    return h + page_end();
  }

  std::string runs_section(const fs::path& from) const {
    std::string h =
        "<section id=\"runs\"><h2>Runs</h2>\n<div class=\"table-wrap\"><table class=\"sortable\">"
        "<thead><tr><th class=\"num\">run</th><th>commit</th><th>run id</th><th>started</th>"
        "<th>folder</th></tr></thead><tbody>\n";
    for (const HistoryRun& r : runs_) h += "<tr>" + run_cells(r, from) + "</tr>\n";
    return h + "</tbody></table></div></section>\n";
  }

  // A run's order, commit, id, start and a link to its folder (and its
  // report) when the folder is on this machine.
  std::string run_cells(const HistoryRun& r, const fs::path& from) const {
    const std::string folder = link_to(r.run_dir, from);
    const std::string report = link_to(fs::path(r.run_dir) / "report" / "index.html", from);
    std::string where = folder.empty() ? "<span class=\"note\">not on this machine</span>"
                                       : "<a href=\"" + folder + "\">folder</a>";
    if (!report.empty()) where += " &middot; <a href=\"" + report + "\">report</a>";
    return "<td class=\"num\">" + std::to_string(r.run_order) + "</td><td class=\"mono\">" +
           html_escape(short_commit(r.commit)) + "</td><td class=\"mono\">" +
           html_escape(r.run_id) + "</td><td>" + html_escape(r.started_at) + "</td><td>" + where +
           "</td>";
  }

  std::string hosts_section() const {
    std::string h = "<section id=\"hosts\"><h2>Hosts</h2>\n<ul>\n";
    for (const std::string& fp : hosts_.fingerprints())
      h += "<li class=\"mono\">" + html_escape(hosts_.label(fp)) + ": " +
           html_escape(fp.empty() ? "records without a host fingerprint" : fp) + "</li>\n";
    return h + "</ul></section>\n";
  }

  // A job's images in a run, as thumbnails linked to the full images.
  std::string thumbnails(std::size_t run, const SeriesJob& job, const fs::path& from,
                         const std::string& side) const {
    std::string h;
    if (!job.present) return h;
    for (const char* name : {"shaded.png", "error.png"}) {
      // Linked only when it is a regular file inside the run folder (the
      // history's job id is input: core/folder_file.h).
      const std::string rel = "jobs/" + job.job_id + "/" + name;
      if (!inside_folder(runs_[run].run_dir, rel)) continue;
      const std::string link = link_to(fs::path(runs_[run].run_dir) / rel, from);
      if (link.empty()) continue;
      const std::string what =
          side + " (run " + std::to_string(runs_[run].run_order) + "): " + name;
      h += "<figure><a href=\"" + link;
      h += "\"><img src=\"" + link;
      h += "\" alt=\"" + html_escape(what);
      h += "\"></a><figcaption>" + html_escape(what) + "</figcaption></figure>";
    }
    return h;
  }

  std::string series_page(std::size_t i) const {
    const SeriesHistory& s = series_[i];
    const fs::path from = (out_ / page(i)).parent_path();
    const std::string stem = fs::path(page(i)).stem().string();
    std::string h = page_head(s.jobs.series) + header(s.jobs.series, "../index.html");
    h += "<figure class=\"chart history-chart\"><img src=\"" +
         html_escape(url_path(stem + ".svg")) + "\" alt=\"" + html_escape(s.jobs.series) +
         ": time and error by run\">"
         "<figcaption>time and error by run <a href=\"" +
         html_escape(url_path(stem + ".png")) +
         "\">PNG</a></figcaption></figure>\n<h2>Steps</h2>\n";
    std::vector<const ReportedStep*> mine;
    for (const ReportedStep& r : steps_)
      if (r.series == s.jobs.series) mine.push_back(&r);
    if (mine.empty()) h += "<p class=\"note\">No step in this series.</p>\n";
    h += "<p class=\"note\">" + html_escape(quantity_label(q().time)) + ": noise between runs " +
         fmt(100 * s.time_sigma, "%.2g") + " %" +
         (s.time_serial_correlation > 0
              ? ", corrected for a serial correlation of " + fmt(s.time_serial_correlation, "%.2f")
              : std::string()) +
         "; a run marked <em>loaded</em> measured more noise of its own than that, weighs "
         "less and counts as half a run toward the 3 a level needs (docs/ci.md, \"How steps "
         "are found\").</p>\n";
    for (const ReportedStep* r : mine) {
      const std::size_t after = r->change.index;
      const std::vector<double>& values = r->quantity == q().time ? s.time : s.error;
      const std::ptrdiff_t before = last_run_with_value(values, after);
      h += steps_table_head() + step_row(*r, html_escape(s.jobs.series)) +
           "</tbody></table></div>\n<table><tbody>";
      if (before >= 0)
        h += "<tr><th>last run before</th>" +
             run_cells(runs_[static_cast<std::size_t>(before)], from) + "</tr>";
      h += "<tr><th>first run after</th>" + run_cells(runs_[after], from) +
           "</tr></tbody></table>\n<div class=\"thumbs\">";
      if (before >= 0)
        h += thumbnails(static_cast<std::size_t>(before),
                        s.jobs.runs[static_cast<std::size_t>(before)], from, "before");
      h += thumbnails(after, s.jobs.runs[after], from, "after") + "</div>\n";
    }
    h += "<h2>Every run</h2>\n<div class=\"table-wrap\"><table class=\"sortable\"><thead><tr>"
         "<th class=\"num\">run</th><th>commit</th><th>host</th><th>status</th><th class=\"num\">" +
         html_escape(quantity_label(q().time)) + "</th><th class=\"num\">its own noise</th>" +
         "<th class=\"num\">" + html_escape(quantity_label(q().error)) +
         "</th></tr></thead><tbody>\n";
    for (std::size_t run = 0; run < runs_.size(); ++run) {
      const SeriesJob& j = s.jobs.runs[run];
      h += "<tr><td class=\"num\">" + std::to_string(runs_[run].run_order) +
           "</td><td class=\"mono\">" + html_escape(short_commit(runs_[run].commit)) + "</td><td>" +
           (j.present ? html_escape(hosts_.label(j.host_fingerprint)) : "") + "</td><td>" +
           (j.present ? html_escape(j.status) : "not in this run") +
           (j.reason.empty() ? "" : ": " + html_escape(j.reason)) + "</td><td class=\"num\">" +
           fmt(s.time[run]) + "</td><td class=\"num\">" + own_noise_cell(s, run) +
           "</td><td class=\"num\">" + fmt(s.error[run]) + "</td></tr>\n";
    }
    h += "</tbody></table></div>\n";
    return h + page_end();
  }

  json steps_json() const {
    json steps = json::array();
    for (const ReportedStep& r : steps_) {
      const ChangePoint& c = r.change;
      steps.push_back({{"series", r.series},
                       {"quantity", r.quantity},
                       {"run_order", r.run_order},
                       {"commit", r.commit},
                       {"previous_commit", r.previous_commit},
                       {"before", c.before},
                       {"after", c.after},
                       {"relative_change", std::isfinite(c.relative_change)
                                               ? json(c.relative_change)
                                               : json(c.relative_change > 0 ? "inf" : "-inf")},
                       {"step_over_sigma", c.step_over_sigma},
                       {"runs_before", c.runs_before},
                       {"runs_after", c.runs_after},
                       {"page", r.page}});
    }
    return {{"history", db_.path()},     {"runs", runs_.size()},        {"series", series_.size()},
            {"time_quantity", q().time}, {"error_quantity", q().error}, {"steps", steps}};
  }

  const HistoryDb& db_;
  fs::path out_;
  const HistoryReportOptions& options_;
  std::vector<HistoryRun> runs_;
  std::vector<SeriesHistory> series_;
  Hosts hosts_;
  std::vector<ReportedStep> steps_;  // newest first
};

}  // namespace

HistoryReport write_history_report(const HistoryDb& db, const std::string& out_dir,
                                   const HistoryReportOptions& options) {
  return Site(db, fs::absolute(out_dir), options).write();
}

}  // namespace sb::history
