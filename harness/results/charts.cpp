#include "results/charts.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/install_layout.h"
#include "core/names.h"
#include "record/figures.h"
#include "record/job_record.h"
#include "results/control_baseline.h"
#include "results/pareto.h"
#include "results/record_groups.h"
#include "store/results_store.h"

extern char** environ;

namespace sb::results {

using core::data_dirs;
using core::file_safe;
using core::InputError;
using core::write_file_atomically;
using record::FineTiming;
using record::JobRecord;
using record::JobStatus;
using record::MetricPath;
using record::Series;
using record::TimingRecord;
using store::json_text;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr const char* kPython = "/usr/bin/python3";
constexpr const char* kScript = "plot_charts.py";
constexpr const char* kInstall = "apt-get install python3-matplotlib";
constexpr int kExitNoMatplotlib = 3;  // plot_charts.py's exit code when the import fails

// ---------------------------------------------------------------- metrics

MetricPath metric_path(const std::string& metric) {
  if (const auto p = MetricPath::parse(metric)) return *p;
  throw InputError("", "--metric",
                   "unknown error metric \"" + metric +
                       "\": expected a dotted path into a record's \"metrics\", " +
                       record::metric_path_syntax());
}

double metric_of(const JobRecord& r, const MetricPath& metric) {
  return r.metric(metric).value_or(std::nan(""));
}

// ---------------------------------------------------------------- records

struct Timing {
  double median = std::nan(""), p10 = std::nan(""), p90 = std::nan("");
};

Timing timing_of(const Series* t) {
  if (t == nullptr) return {};
  return {t->median, t->p10, t->p90};
}

// The frame's timing, or the technique's.
Timing timing_of(const JobRecord& r, Series TimingRecord::*series) {
  return r.timing ? timing_of(&(*r.timing.*series)) : Timing{};
}

const Series* shared_pass(const JobRecord& r, const std::string& name) {
  if (!r.timing) return nullptr;
  const auto it = r.timing->shared.find(name);
  return it == r.timing->shared.end() ? nullptr : &it->second;
}

// Ordinal of each name in first-appearance order (stable colours and markers
// for a technique variant or a pass across every chart).
class Palette {
 public:
  int operator()(const std::string& name) {
    return index_.emplace(name, static_cast<int>(index_.size())).first->second;
  }

 private:
  std::map<std::string, int> index_;
};

bool spans_decade(const std::vector<double>& values) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  return std::isfinite(lo) && hi > 10.0 * lo;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json timed_point(double x, const Timing& t) {
  return {
      {"x", x}, {"y", t.median}, {"ylo", finite_or_null(t.p10)}, {"yhi", finite_or_null(t.p90)}};
}

// json's move constructor calls assert_invariant(), which clang-tidy cannot
// prove noexcept; it is.
// NOLINTNEXTLINE(bugprone-exception-escape)
struct Chart {
  ChartFile file;
  json data;
};

Chart make_chart(const std::string& kind, const std::string& stem, const std::string& title,
                 const std::string& out_dir) {
  Chart c;
  c.file.kind = kind;
  c.file.title = title;
  c.file.svg = (fs::path(out_dir) / (stem + ".svg")).string();
  c.file.png = (fs::path(out_dir) / (stem + ".png")).string();
  c.data = {{"kind", kind}, {"title", title}, {"svg", c.file.svg}, {"png", c.file.png}};
  return c;
}

// Charts of one (scene variant, resolution): <kind>__<scene>__<WxH>.
Chart scene_chart(const std::string& kind, const std::string& what, const JobRecord& r,
                  const std::string& out_dir) {
  const std::string scene = r.scene_variant, res = r.resolution;
  return make_chart(kind, kind + "__" + file_safe(scene) + "__" + file_safe(res),
                    what + ": " + scene + " @ " + res, out_dir);
}

constexpr const char* kTimeLabel = "median frame time (ms; bars p10–p90)";

// A cost for the error charts' x axis: a value with an optional spread
// (NaN: none), and NaN for a record without one.
struct Cost {
  double x = std::nan(""), lo = std::nan(""), hi = std::nan("");
};

// The error against a cost per (scene variant, resolution): one point per
// technique variant and the Pareto front of (cost, error). No chart for a
// (scene, resolution) where no record has the cost.
void error_cost_charts(const std::vector<const JobRecord*>& ok, const std::string& metric,
                       const std::string& kind, const std::string& cost_name,
                       const std::string& xlabel,
                       const std::function<Cost(const JobRecord&)>& cost_of, Palette& styles,
                       const std::string& out_dir, std::vector<Chart>& out) {
  const MetricPath path = metric_path(metric);
  const bool higher = path.higher_is_better();
  const std::string what = metric + " vs " + cost_name;
  for (const auto& [key, records] : by_scene_and_resolution(ok)) {
    Chart c = scene_chart(kind, what, *records[0], out_dir);
    json points = json::array(), missing = json::array();
    std::vector<ParetoPoint> pp;
    std::vector<double> xs;
    for (const JobRecord* r : records) {
      const std::string label = r->technique_variant;
      const Cost cost = cost_of(*r);
      const double e = metric_of(*r, path);
      if (!std::isfinite(cost.x) || !std::isfinite(e)) {
        missing.push_back(label);
        continue;
      }
      // The control is drawn as a reference, never on the front.
      const bool control = is_control(records, *r);
      c.file.series.push_back(label);
      points.push_back({{"label", label},
                        {"style", styles(label)},
                        {"x", cost.x},
                        {"xlo", finite_or_null(cost.lo)},
                        {"xhi", finite_or_null(cost.hi)},
                        {"y", e},
                        {"control", control}});
      if (!control) pp.push_back({cost.x, higher ? -e : e, label});
      xs.push_back(cost.x);
    }
    json front = json::array();
    for (const ParetoPoint& p : pareto_front(pp)) {
      c.file.pareto.push_back(p.label);
      front.push_back({{"label", p.label}, {"x", p.time}, {"y", higher ? -p.error : p.error}});
    }
    // A log axis cannot show a cost of 0 (a technique that holds no memory).
    const bool has_zero = std::any_of(xs.begin(), xs.end(), [](double x) { return x <= 0.0; });
    c.data.update({{"xlabel", xlabel},
                   {"ylabel", metric + (higher ? " (higher is better)" : " (lower is better)")},
                   {"xlog", spans_decade(xs) && !has_zero},
                   {"ylog", false},
                   {"higher_is_better", higher},
                   {"points", points},
                   {"front", front},
                   {"missing", missing}});
    if (!points.empty()) out.push_back(std::move(c));
  }
}

// Error against frame time per (scene variant, resolution).
void error_time_charts(const std::vector<const JobRecord*>& ok, const std::string& metric,
                       Palette& styles, const std::string& out_dir, std::vector<Chart>& out) {
  error_cost_charts(
      ok, metric, "error_time", "frame time", kTimeLabel,
      [](const JobRecord& r) {
        const Timing t = timing_of(r, &TimingRecord::frame);
        return Cost{t.median, t.p10, t.p90};
      },
      styles, out_dir, out);
}

// Error against the technique's GPU memory, its own and its needs'
// (technique.gpu_bytes), per (scene variant, resolution), where the records
// have that total (older records counted the technique's own only).
void error_memory_charts(const std::vector<const JobRecord*>& ok, const std::string& metric,
                         Palette& styles, const std::string& out_dir, std::vector<Chart>& out) {
  error_cost_charts(
      ok, metric, "error_memory", "GPU memory",
      "GPU memory: the technique's peak and its needs' (MiB)",
      [](const JobRecord& r) {
        Cost c;
        if (const auto bytes = r.technique.gpu_total_bytes())
          c.x = static_cast<double>(*bytes) / (1024.0 * 1024.0);
        return c;
      },
      styles, out_dir, out);
}

// One series per technique variant of (x, y) points over `records`: y is a
// point's JSON ({"y", "ylo", "yhi"}) or null to leave the record out.
json line_series(const std::vector<const JobRecord*>& records,
                 const std::function<double(const JobRecord&)>& x,
                 const std::function<json(const JobRecord&)>& y, Palette& styles, Chart& c) {
  json series = json::array();
  std::vector<double> ys;
  for (const auto& [label, rs] :
       group_by(records, [](const JobRecord& r) { return r.technique_variant; })) {
    std::vector<std::pair<double, json>> pts;
    for (const JobRecord* r : rs) {
      json point = y(*r);
      if (!point.is_null() && std::isfinite(x(*r))) pts.emplace_back(x(*r), std::move(point));
    }
    if (pts.empty()) continue;
    std::stable_sort(pts.begin(), pts.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    json p = json::array();
    for (auto& [xv, point] : pts) {
      point["x"] = xv;
      ys.push_back(point["y"].get<double>());
      p.push_back(std::move(point));
    }
    c.file.series.push_back(label);
    series.push_back({{"label", label}, {"style", styles(label)}, {"points", p}});
  }
  c.data["ylog"] = spans_decade(ys);
  return series;
}

// One series per technique variant of (x, frame time) over `records`.
json time_series(const std::vector<const JobRecord*>& records,
                 const std::function<double(const JobRecord&)>& x, Palette& styles, Chart& c) {
  return line_series(
      records, x,
      [](const JobRecord& r) -> json {
        const Timing t = timing_of(r, &TimingRecord::frame);
        return std::isfinite(t.median) ? timed_point(0.0, t) : json(nullptr);
      },
      styles, c);
}

double triangles_of(const JobRecord& r) {
  return r.scene.built ? static_cast<double>(r.scene.built->triangles) : std::nan("");
}

double pixels_of(const JobRecord& r) {
  return static_cast<double>(r.width) * static_cast<double>(r.height);
}

// One chart of `kind` per (scene type, resolution) whose scene variants have
// two or more triangle counts, x = scene.triangles; `y` names the y axis and
// fills the series.
void triangles_charts(const std::vector<const JobRecord*>& ok, const std::string& kind,
                      const std::string& quantity, const std::string& ylabel,
                      const std::function<json(const std::vector<const JobRecord*>&, Chart&)>& y,
                      const std::string& out_dir, std::vector<Chart>& out) {
  const auto groups =
      group_by(ok, [](const JobRecord& r) { return r.scene.type + "\n" + r.resolution; });
  for (const auto& [key, records] : groups) {
    std::set<double> counts;
    for (const JobRecord* r : records)
      if (std::isfinite(triangles_of(*r))) counts.insert(triangles_of(*r));
    if (counts.size() < 2) continue;
    const std::string& type = records[0]->scene.type;
    const std::string& res = records[0]->resolution;
    std::string title = quantity + " vs triangles: ";
    title.append(type).append(" @ ").append(res);
    Chart c =
        make_chart(kind, kind + "__" + file_safe(type) + "__" + file_safe(res), title, out_dir);
    c.data["series"] = y(records, c);
    c.data.update({{"xlabel", "triangles (scene.triangles)"},
                   {"ylabel", ylabel},
                   {"xlog", spans_decade({counts.begin(), counts.end()})}});
    out.push_back(std::move(c));
  }
}

// Frame time against scene.triangles.
void time_triangles_charts(const std::vector<const JobRecord*>& ok, Palette& styles,
                           const std::string& out_dir, std::vector<Chart>& out) {
  triangles_charts(
      ok, "time_triangles", "frame time", kTimeLabel,
      [&](const std::vector<const JobRecord*>& records, Chart& c) {
        return time_series(records, triangles_of, styles, c);
      },
      out_dir, out);
}

// The error metric against scene.triangles: how a technique's error follows
// the tessellation of the same shapes.
void error_triangles_charts(const std::vector<const JobRecord*>& ok, const std::string& metric,
                            Palette& styles, const std::string& out_dir, std::vector<Chart>& out) {
  const MetricPath path = metric_path(metric);
  const bool higher = path.higher_is_better();
  triangles_charts(
      ok, "error_triangles", metric,
      metric + (higher ? " (higher is better)" : " (lower is better)"),
      [&](const std::vector<const JobRecord*>& records, Chart& c) {
        return line_series(
            records, triangles_of,
            [&](const JobRecord& r) -> json {
              const double e = metric_of(r, path);
              if (!std::isfinite(e)) return nullptr;
              return {{"y", e}, {"ylo", nullptr}, {"yhi", nullptr}};
            },
            styles, c);
      },
      out_dir, out);
}

// Frame time against width×height per scene variant.
void time_resolution_charts(const std::vector<const JobRecord*>& ok, Palette& styles,
                            const std::string& out_dir, std::vector<Chart>& out) {
  for (const auto& [scene, records] :
       group_by(ok, [](const JobRecord& r) { return r.scene_variant; })) {
    std::map<double, std::string> sizes;  // pixels → "WxH"
    for (const JobRecord* r : records)
      if (pixels_of(*r) > 0) sizes.emplace(pixels_of(*r), r->resolution);
    if (sizes.size() < 2) continue;
    Chart c = make_chart("time_resolution", "time_resolution__" + file_safe(scene),
                         "frame time vs resolution: " + scene, out_dir);
    c.data["series"] = time_series(records, pixels_of, styles, c);
    json ticks = json::array();
    std::vector<double> xs;
    for (const auto& [px, label] : sizes) {
      ticks.push_back({{"value", px}, {"label", label}});
      xs.push_back(px);
    }
    c.data.update({{"xlabel", "pixels (width × height)"},
                   {"ylabel", kTimeLabel},
                   {"xlog", spans_decade(xs)},
                   {"xticks", ticks}});
    out.push_back(std::move(c));
  }
}

// Stacked bars of median pass times per (scene variant, resolution): the
// technique's passes with --pass-timing fine, else its one bracket.
void passes_charts(const std::vector<const JobRecord*>& ok, Palette& pass_colours,
                   const std::string& out_dir, std::vector<Chart>& out) {
  for (const auto& [key, records] : by_scene_and_resolution(ok)) {
    Chart c = scene_chart("passes", "time per pass", *records[0], out_dir);
    json bars = json::array();
    for (const JobRecord* r : records) {
      json segments = json::array();
      auto add = [&](const std::string& name, const Series* series, bool shared) {
        const double ms = timing_of(series).median;
        if (!std::isfinite(ms)) return;
        segments.push_back({{"name", shared ? name + " (shared)" : name},
                            {"ms", ms},
                            {"shared", shared},
                            {"style", shared ? -1 : pass_colours(name)}});
      };
      add("gbuffer", shared_pass(*r, "gbuffer"), true);
      add("shading", shared_pass(*r, "shading"), true);
      const FineTiming* fine = r->timing && r->timing->fine ? &*r->timing->fine : nullptr;
      // A coarse run (the default) times the technique as one bracket: one
      // segment then, so the bar is never just the shared passes.
      if (fine == nullptr || fine->pass_order.empty())
        add("technique (all passes)", r->timing ? &r->timing->technique : nullptr, false);
      if (fine != nullptr)
        for (const auto& name : fine->pass_order) add(name, &fine->passes.at(name), false);
      if (segments.empty()) continue;
      c.file.series.push_back(r->technique_variant);
      bars.push_back({{"label", r->technique_variant}, {"segments", segments}});
    }
    c.data.update({{"ylabel", "median time (ms)"}, {"bars", bars}});
    if (!bars.empty()) out.push_back(std::move(c));
  }
}

// ---------------------------------------------------------------- python

// Runs argv without a shell; stdout and stderr end up in *output.
int run_process(const std::vector<std::string>& argv, std::string* output) {
  std::string tmpl = (fs::temp_directory_path() / "shadowbench_plot_XXXXXX").string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary file for python's output");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fd, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int err = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fd);
  int status = 0;
  if (err == 0)
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  {
    std::ifstream in(tmpl, std::ios::binary);
    output->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ::unlink(tmpl.c_str());
  if (err != 0) throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(err));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

void require_python() {
  if (::access(kPython, X_OK) != 0)
    throw std::runtime_error(std::string("charts need ") + kPython +
                             " with matplotlib, and it is missing: " + kInstall);
}

}  // namespace

std::string find_plot_script() {
  std::vector<std::string> dirs = data_dirs();
#ifdef SHADOWBENCH_CHARTS_SOURCE_DIR
  dirs.emplace_back(SHADOWBENCH_CHARTS_SOURCE_DIR);
#endif
  std::string tried;
  std::error_code ec;
  for (const auto& d : dirs) {
    const fs::path script = fs::path(d) / kScript;
    if (fs::is_regular_file(script, ec)) return script.string();
    tried += (tried.empty() ? "" : ", ") + d;
  }
  throw std::runtime_error(std::string("cannot find ") + kScript + " (looked in " + tried +
                           "; set SHADOWBENCH_SHARE_DIR to its folder)");
}

std::string charts_unavailable_reason() {
  if (::access(kPython, X_OK) != 0) return std::string(kPython) + " is missing: " + kInstall;
  std::string output;
  if (run_process({kPython, "-c", "import matplotlib"}, &output) != 0)
    return std::string(kPython) + " cannot import matplotlib: " + kInstall;
  return "";
}

std::vector<ChartFile> write_charts(const std::vector<JobRecord>& records,
                                    const std::string& out_dir, const ChartOptions& options) {
  std::vector<const JobRecord*> ok;
  for (const JobRecord& r : records)
    if (r.status == JobStatus::Ok) ok.push_back(&r);
  metric_path(options.error_metric);  // an unknown metric is bad input, drawn or not
  if (options.style != "default" && options.style != "paper")
    throw InputError("", "--style",
                     "unknown chart style \"" + options.style + "\": expected default or paper");

  Palette styles, pass_colours;  // in plan order, failed jobs included: stable across reruns
  for (const JobRecord& r : records) styles(r.technique_variant);
  std::vector<Chart> charts;
  error_time_charts(ok, options.error_metric, styles, out_dir, charts);
  error_memory_charts(ok, options.error_metric, styles, out_dir, charts);
  time_triangles_charts(ok, styles, out_dir, charts);
  error_triangles_charts(ok, options.error_metric, styles, out_dir, charts);
  time_resolution_charts(ok, styles, out_dir, charts);
  passes_charts(ok, pass_colours, out_dir, charts);
  if (charts.empty()) return {};

  if (options.style == "paper")
    for (Chart& c : charts) {
      c.file.pdf = fs::path(c.file.svg).replace_extension(".pdf").string();
      c.data.update({{"style", "paper"}, {"pdf", c.file.pdf}});
    }

  fs::create_directories(out_dir);
  std::vector<std::string> data_files;
  for (const Chart& c : charts) {
    data_files.push_back(fs::path(c.file.svg).replace_extension(".json").string());
    write_file_atomically(data_files.back(), json_text(c.data, 1) + "\n");
  }
  draw_chart_data(data_files);

  std::vector<ChartFile> out;
  out.reserve(charts.size());
  for (Chart& c : charts) out.push_back(std::move(c.file));
  return out;
}

void draw_chart_data(const std::vector<std::string>& data_files) {
  if (data_files.empty()) return;
  require_python();
  const std::string script = find_plot_script();
  std::vector<std::string> argv = {kPython, script};
  argv.insert(argv.end(), data_files.begin(), data_files.end());
  std::string output;
  const int rc = run_process(argv, &output);
  if (rc == kExitNoMatplotlib)
    throw std::runtime_error(std::string(kPython) + " cannot import matplotlib: " + kInstall +
                             "\n" + output);
  if (rc != 0)
    throw std::runtime_error(script + " failed (exit " + std::to_string(rc) + "):\n" + output);
}

}  // namespace sb::results
