// shadowbench — the command-line driver.
//   shadowbench run CONFIG [--out DIR] [--backend osmesa|egl] [--cache-dir DIR]
//                          [--no-cache] [--no-images] [--gbuffer] [--plugins DIR] [--quiet]
//                          [--benchmark-out FILE] [--bencher-out FILE] [--embree-config CFG]
//                          [--max-jobs N] [--pass-timing coarse|fine]
//   shadowbench validate CONFIG [--plugins DIR] [--max-jobs N]
//   shadowbench plan CONFIG [--plugins DIR] [--max-jobs N]
//   shadowbench list [--plugins DIR] [--markdown]
//   shadowbench report RUN_DIR [--out DIR] [--metric PATH]
//                             [--benchmark-out FILE] [--bencher-out FILE]
//   shadowbench compare BASE_DIR NEW_DIR [--alpha A] [--time-threshold R]
//                       [--error-threshold E] [--metric PATH]
//                       [--timing frame|technique|none] [--normalize none|control]
//   shadowbench compare-builds --base BIN_A --new BIN_B CONFIG [--out DIR]
//                       [--turn-block N] [compare's options]
//   shadowbench scene export SCENE-SPEC OUT.glb
//   shadowbench scene info FILE.glb|FILE.gltf|SCENE-SPEC
// Exit codes: 0 all jobs ok or skipped, 1 some job failed, 2 bad input
// (config, arguments), 3 environment (no GL context, missing plugins),
// 4 (compare) a significant regression over threshold; compare exits 2 too
// when it could not compare some job's time (other hosts, no control).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "config/param_table.h"
#include "config/unread_params.h"
#include "core/error.h"
#include "core/scene_types.h"
#include "plan/plan.h"
#include "plugin/registry.h"
#include "reference/embree_isa.h"
#include "results/bencher_json.h"
#include "results/benchmark_json.h"
#include "results/charts.h"
#include "results/compare.h"
#include "results/html_report.h"
#include "results/report.h"
#include "results/store.h"
#include "run/runner.h"
#include "run/take_turns.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
#include "scenes/need_providers.h"
#include "scenes/scene_spec.h"

namespace {

using namespace sb;

constexpr const char* kUsage =
    "usage:\n"
    "  shadowbench run CONFIG [--out DIR] [--backend osmesa|egl] [--cache-dir DIR]\n"
    "                         [--no-cache] [--no-images] [--gbuffer] [--plugins DIR] [--quiet]\n"
    "                         [--embree-config isa=avx2|max_isa=avx2] [--max-jobs 10000]\n"
    "                         [--pass-timing coarse|fine]\n"
    "  shadowbench validate CONFIG [--plugins DIR] [--max-jobs 10000]\n"
    "  shadowbench plan CONFIG [--plugins DIR] [--max-jobs 10000]\n"
    "  shadowbench list [--plugins DIR] [--markdown]\n"
    "  shadowbench report RUN_DIR [--out DIR] [--metric visibility.all.rmse]\n"
    "  (run and report also take --benchmark-out FILE (Google Benchmark JSON)\n"
    "   and --bencher-out FILE (Bencher Metric Format JSON))\n"
    "  shadowbench compare BASE_DIR NEW_DIR [--alpha 0.02] [--time-threshold 0.10]\n"
    "                      [--error-threshold 0.005] [--metric visibility.all.rmse]\n"
    "                      [--timing frame|technique|none] [--normalize none|control]\n"
    "  shadowbench compare-builds --base BIN_A --new BIN_B CONFIG [--out DIR]\n"
    "                      [--turn-block 5] [compare's options]\n"
    "    (runs both builds on CONFIG taking turns, block of frames by block of\n"
    "     frames, then compares them, by default --normalize control: the A/B\n"
    "     mode for pull requests, docs/ci.md)\n"
    "  shadowbench scene export SCENE-SPEC OUT.glb\n"
    "  shadowbench scene info FILE.glb|FILE.gltf|SCENE-SPEC\n"
    "SCENE-SPEC: sphere_grid:grid=3,light_size=2 or "
    "'{\"type\":\"sphere_grid\",\"params\":{...}}'\n";

struct Args {
  std::string command;
  std::vector<std::string> positional;
  std::string out, backend = "osmesa", cache_dir = "results/cache", plugins;
  bool no_cache = false, no_images = false, gbuffer = false, quiet = false;
  bool markdown = false;                                // list
  std::string benchmark_out, bencher_out;               // run, report: CI outputs
  std::string embree_config;                            // run: the reference's Embree ISA
  gl::PassDetail pass_detail = gl::PassDetail::Coarse;  // run
  ExperimentLimits limits;                              // run, validate
  CompareOptions compare;                               // compare
  std::string base_binary, new_binary;                  // compare-builds
  std::string take_turns;                               // run: IN_FD,OUT_FD (compare-builds)
  int turn_block = 5;                                   // run, compare-builds: frames per turn
  bool turn_block_given = false;
  bool compare_options_given = false;
  bool normalize_given = false;  // compare-builds defaults to "control"
  bool metric_given = false;
};

double parse_number(const std::string& option, const std::string& text) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw InputError("", option, "expected a number, found '" + text + "'");
  return v;
}

// A whole number in [lo, hi], or InputError naming the option.
double parse_whole(const std::string& option, const std::string& text, double lo, double hi,
                   const char* what) {
  const double v = parse_number(option, text);
  if (!(v >= lo && v <= hi && v == std::floor(v))) throw InputError("", option, what);
  return v;
}

Args parse_args(int argc, char** argv) {
  Args a;
  if (argc < 2) throw InputError("", "command line", std::string("expected a command\n") + kUsage);
  a.command = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* name) {
      if (i + 1 >= argc) throw InputError("", name, "expected a value after it");
      return std::string(argv[++i]);
    };
    if (s == "--out")
      a.out = value("--out");
    else if (s == "--backend")
      a.backend = value("--backend");
    else if (s == "--cache-dir")
      a.cache_dir = value("--cache-dir");
    else if (s == "--plugins")
      a.plugins = value("--plugins");
    else if (s == "--benchmark-out")
      a.benchmark_out = value("--benchmark-out");
    else if (s == "--bencher-out")
      a.bencher_out = value("--bencher-out");
    else if (s == "--base")
      a.base_binary = value("--base");
    else if (s == "--new")
      a.new_binary = value("--new");
    else if (s == "--take-turns")
      a.take_turns = value("--take-turns");
    else if (s == "--turn-block") {
      a.turn_block = int(parse_whole(s, value("--turn-block"), 1, 100000,
                                     "expected a whole number of frames in [1, 100000]"));
      a.turn_block_given = true;
    } else if (s == "--max-jobs") {
      a.limits.max_jobs = uint64_t(
          parse_whole(s, value("--max-jobs"), 1, 1e12, "expected a whole number in [1, 1e12]"));
    } else if (s == "--embree-config") {
      a.embree_config = value("--embree-config");
      try {
        reference::check_embree_config(a.embree_config);
      } catch (const std::invalid_argument& ex) {
        throw InputError("", "--embree-config", ex.what());
      }
    } else if (s == "--pass-timing") {
      try {
        a.pass_detail = gl::pass_detail_from_string(value("--pass-timing"));
      } catch (const std::invalid_argument& ex) {
        throw InputError("", "--pass-timing", ex.what());
      }
    } else if (s == "--alpha" || s == "--time-threshold" || s == "--error-threshold") {
      const double v = parse_number(s, value(s.c_str()));
      (s == "--alpha"            ? a.compare.alpha
       : s == "--time-threshold" ? a.compare.time_threshold
                                 : a.compare.error_threshold) = v;
      a.compare_options_given = true;
    } else if (s == "--metric") {
      a.compare.metric = value("--metric");  // compare's error check, report's charts
      a.metric_given = true;
    } else if (s == "--timing") {
      a.compare.timing = value("--timing");
      a.compare_options_given = true;
    } else if (s == "--normalize") {
      a.compare.normalize = value("--normalize");
      a.compare_options_given = true;
      a.normalize_given = true;
    } else if (s == "--no-cache")
      a.no_cache = true;
    else if (s == "--gbuffer")
      a.gbuffer = true;
    else if (s == "--no-images")
      a.no_images = true;
    else if (s == "--quiet")
      a.quiet = true;
    else if (s == "--markdown")
      a.markdown = true;
    else if (s.rfind("--", 0) == 0)
      throw InputError("", s, std::string("unknown option\n") + kUsage);
    else
      a.positional.push_back(s);
  }
  return a;
}

Registry load_registry(const Args& a) {
  Registry r;
  const std::string dir = a.plugins.empty() ? default_plugin_dir() : a.plugins;
  try {
    if (r.load_plugins(dir) == 0) throw std::runtime_error("no technique plugins in " + dir);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "shadowbench: %s\n", e.what());
    std::exit(kExitInternal);
  }
  return r;
}

std::string one_config(const Args& a) {
  if (a.positional.size() != 1)
    throw InputError("", "command line",
                     "expected exactly one CONFIG file\n" + std::string(kUsage));
  return a.positional[0];
}

std::string default_run_id(const std::string& name) {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", &tm);
  return name + "-" + buf;
}

// --benchmark-out and --bencher-out of run and report.
void write_ci_outputs(const Args& a, const std::vector<JobRecord>& records) {
  if (!a.benchmark_out.empty()) {
    write_benchmark_json(a.benchmark_out, records);
    std::printf("Google Benchmark JSON: %s\n", a.benchmark_out.c_str());
  }
  if (!a.bencher_out.empty()) {
    write_bencher_json(a.bencher_out, records);
    std::printf("Bencher Metric Format JSON: %s\n", a.bencher_out.c_str());
  }
}

// Needs as the technique declared them (plugin/needs.h).
std::string needs_of(const TechniqueInfo& t) {
  std::string needs;
  for (const auto& n : t.needs.names) needs += " " + n;
  return needs;
}

// docs/parameters.md is this output: generated from the ParamSpecs.
int cmd_list_markdown(const Registry& r) {
  std::printf(
      "# Parameters\n\nGenerated by `shadowbench list --markdown` from the parameter\n"
      "declarations themselves; a test keeps this file equal to its output.\n\n"
      "## Techniques\n");
  for (const auto& t : r.all()) {
    const std::string needs = needs_of(t);
    std::printf("\n### %s\n\n%s (family `%s`).%s\n\n%s", t.name.c_str(), t.summary.c_str(),
                t.family.c_str(), needs.empty() ? "" : (" Needs:" + needs + ".").c_str(),
                markdown_param_table(t.params).c_str());
  }
  std::printf("\n## Scenes\n");
  for (const auto& s : scene_types())
    std::printf("\n### %s\n\n%s\n\n%s", s.name.c_str(), s.summary.c_str(),
                markdown_param_table(s.params).c_str());
  return kExitOk;
}

int cmd_list(const Args& a) {
  const Registry r = load_registry(a);
  if (a.markdown) return cmd_list_markdown(r);
  std::printf("techniques:\n");
  for (const auto& t : r.all()) {
    const std::string needs = needs_of(t);
    std::printf("  %-16s [%s] %s%s\n", t.name.c_str(), t.family.c_str(), t.summary.c_str(),
                needs.empty() ? "" : ("  needs:" + needs).c_str());
    for (const auto& p : t.params) {
      std::string extra;
      if (!p.choices.empty()) {
        for (const auto& c : p.choices) extra += (extra.empty() ? "" : "|") + c;
        extra.insert(0, " {");
        extra += "}";
      }
      std::printf("      %-14s %-8s default %-8s %s%s\n", p.name.c_str(), to_string(p.type).c_str(),
                  p.default_value.dump().c_str(), p.doc.c_str(), extra.c_str());
    }
  }
  std::printf("needs:\n");
  const auto print_need = [](const NeedProvider& p, const char* from) {
    std::printf("  %-18s %s%s\n", p.name.c_str(), p.summary.c_str(), from);
  };
  for (const auto& p : builtin_need_providers()) print_need(p, "");
  for (const auto& p : r.providers()) print_need(p, "  (plugin)");
  std::printf("scenes:\n");
  for (const auto& s : scene_types()) {
    std::printf("  %-16s %s\n", s.name.c_str(), s.summary.c_str());
    for (const auto& p : s.params)
      std::printf("      %-14s %-8s default %-8s %s\n", p.name.c_str(), to_string(p.type).c_str(),
                  p.default_value.dump().c_str(), p.doc.c_str());
  }
  return kExitOk;
}

// Parameters a technique declares but never reads (config/unread_params.h).
void warn_unread_parameters(const Experiment& e) {
  for (const std::string& w : unread_parameter_warnings(e))
    std::fprintf(stderr, "shadowbench: warning: %s\n", w.c_str());
}

// Both plan every job on the CPU, no GL: a bad scene file is found now, and
// the counts say which jobs will be skipped and why.
int cmd_validate(const Args& a, bool show_plan) {
  const Registry r = load_registry(a);
  const Experiment e = load_experiment(one_config(a), r, a.limits);
  warn_unread_parameters(e);
  const Plan plan = make_plan(e);
  if (show_plan) std::printf("%s", describe_plan(e, plan).c_str());
  for (size_t s = 0; s < plan.scenes.size(); ++s) {
    const ScenePlan& sp = plan.scenes[s];
    if (sp.error.empty()) continue;
    const std::string what =
        sp.bad_input
            ? sp.input_error
            : InputError(e.file, e.scenes[s].pointer, "scene " + e.scenes[s].name + ": " + sp.error)
                  .what();
    std::fprintf(stderr, "shadowbench: error: %s\n", what.c_str());
    return kExitBadInput;
  }
  if (!show_plan)
    std::printf(
        "%s: ok: %zu scene variant(s) × %zu resolution(s) × %zu technique variant(s) = %zu jobs "
        "(%zu to run, %zu skipped; `shadowbench plan` says why)\n",
        e.file.c_str(), e.scenes.size(), e.resolutions.size(), e.techniques.size(),
        plan.jobs.size(), plan.count(PlannedJob::Status::Run),
        plan.count(PlannedJob::Status::Skip));
  return kExitOk;
}

int cmd_run(const Args& a) {
  const Registry r = load_registry(a);
  const Experiment e = load_experiment(one_config(a), r, a.limits);
  warn_unread_parameters(e);
  RunOptions o;
  o.backend = gl::backend_from_string(a.backend);
  if (a.out.empty()) {
    o.run_id = default_run_id(e.name);
    o.run_dir = "results/" + o.run_id;
  } else {
    o.run_dir = a.out;
    o.run_id = std::filesystem::path(a.out).lexically_normal().filename().string();
    if (o.run_id.empty())
      o.run_id = std::filesystem::path(a.out).lexically_normal().parent_path().filename().string();
  }
  o.cache_dir = a.no_cache ? "" : a.cache_dir;
  o.write_images = !a.no_images;
  o.write_gbuffer = a.gbuffer;
  o.quiet = a.quiet;
  o.embree_config = a.embree_config;
  o.pass_detail = a.pass_detail;
  o.turn_block_frames = a.turn_block;
  std::optional<TurnTaker> turns;
  if (!a.take_turns.empty()) {
    turns = TurnTaker::parse(a.take_turns);
    o.take_turn = [&turns](const std::string& what) { turns->take(what); };
  }
  RunSummary s;
  try {
    // In an interleaved A/B run nothing, not even the scene's set-up,
    // overlaps the other build's turn.
    if (turns) turns->take("start");
    s = run_experiment(e, o);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "shadowbench: %s\n", ex.what());
    return kExitInternal;
  }
  if (!a.quiet) {
    const auto md = make_markdown(read_job_records(o.run_dir), e.name + " (" + o.run_id + ")");
    std::printf("\n%s\n", md.c_str());
  }
  std::printf("%d ok, %d skipped, %d failed, %d resumed", s.ok, s.skipped, s.failed, s.resumed);
  if (s.respecified > 0)
    std::printf(" (%d earlier records had other settings and were rerun)", s.respecified);
  std::printf("; results in %s\n", o.run_dir.c_str());
  if (!a.benchmark_out.empty() || !a.bencher_out.empty())
    write_ci_outputs(a, read_job_records(o.run_dir));
  if (s.bad_input > 0) return kExitBadInput;
  return s.failed > 0 ? kExitJobsFailed : kExitOk;
}

// report and compare read run folders that anyone may have written: a record
// that does not follow the schema is bad input (read_job_records names the
// file, the line and the JSON pointer), not an internal error.
int cmd_report(const Args& a) {
  if (a.positional.size() != 1) throw InputError("", "command line", "expected one RUN_DIR");
  const auto records = read_job_records(a.positional[0]);
  const std::string title =
      records.empty() ? "shadowbench" : records[0].experiment + " (" + records[0].run_id + ")";
  const std::string& run_dir = a.positional[0];
  write_reports(run_dir, records, title);
  std::printf("%s", make_markdown(records, title).c_str());
  // Charts and index.html go to --out, by default RUN_DIR/report.
  const std::string out =
      a.out.empty() ? (std::filesystem::path(run_dir) / "report").string() : a.out;
  std::filesystem::create_directories(out);
  ChartOptions chart_options;
  chart_options.error_metric = a.compare.metric;
  std::vector<ReportChart> charts;
  for (const ChartFile& c : write_charts(records, out, chart_options)) {
    charts.push_back({c.title, c.svg, c.png});
    std::printf("chart: %s (.png)\n", c.svg.c_str());
  }
  write_html_report(records, run_dir, out, charts, title);
  std::printf("report: %s\n", (std::filesystem::path(out) / "index.html").string().c_str());
  write_ci_outputs(a, records);
  return kExitOk;
}

int cmd_compare(const Args& a) {
  if (a.positional.size() != 2)
    throw InputError("", "command line", "expected BASE_DIR NEW_DIR\n" + std::string(kUsage));
  std::vector<JobRecord> runs[2];
  for (int i = 0; i < 2; ++i) {
    const std::string& dir = a.positional[size_t(i)];
    if (!std::filesystem::is_directory(dir)) throw InputError(dir, "", "no such run directory");
    runs[i] = read_job_records(dir);
    if (runs[i].empty()) throw InputError(dir + "/results.jsonl", "", "no records");
  }
  const CompareResult r = compare_runs(runs[0], runs[1], a.compare);
  if (r.jobs.empty())
    throw InputError(a.positional[1], "", "no job in common with " + a.positional[0]);
  auto describe = [](const std::vector<JobRecord>& records, const std::string& dir) {
    const std::string& id = records[0].run_id;
    return dir + (id.empty() ? "" : " (" + id + ")");
  };
  std::printf("BASE %s\nNEW  %s\n", describe(runs[0], a.positional[0]).c_str(),
              describe(runs[1], a.positional[1]).c_str());
  std::printf("%s", format_comparison(r, a.compare).c_str());
  if (r.regressions > 0) std::fprintf(stderr, "shadowbench: %d job(s) regressed\n", r.regressions);
  if (r.time_refused > 0)
    std::fprintf(
        stderr,
        "shadowbench: the time of %d job(s) was not compared (other or unknown hosts, or no "
        "control timing): use --normalize control, or --timing none for errors only\n",
        r.time_refused);
  return compare_exit_code(r);
}

// Both builds run CONFIG taking turns (run/take_turns.h), each into its own
// folder under --out, then the two are compared as `compare` does.
int cmd_compare_builds(const Args& a) {
  if (a.base_binary.empty() || a.new_binary.empty())
    throw InputError("", "command line",
                     "compare-builds needs --base BIN_A and --new BIN_B\n" + std::string(kUsage));
  const std::string config = one_config(a);
  for (const std::string* bin : {&a.base_binary, &a.new_binary})
    if (::access(bin->c_str(), X_OK) != 0)
      throw InputError(*bin, "", "not an executable shadowbench binary");
  if (!std::filesystem::is_regular_file(config)) throw InputError(config, "", "no such config");
  check_options(a.compare);
  const std::string out = a.out.empty() ? "results/" + default_run_id("compare-builds") : a.out;
  const std::string dirs[2] = {out + "/base", out + "/new"};
  TurnCommand commands[2];
  for (int i = 0; i < 2; ++i) {
    TurnCommand& c = commands[i];
    c.label = i == 0 ? "base" : "new";
    c.argv = {i == 0 ? a.base_binary : a.new_binary,
              "run",
              config,
              "--out",
              dirs[i],
              "--quiet",
              "--no-images",
              "--turn-block",
              std::to_string(a.turn_block),
              "--backend",
              a.backend};
    if (a.no_cache)
      c.argv.push_back("--no-cache");
    else
      c.argv.insert(c.argv.end(), {"--cache-dir", a.cache_dir});
    if (!a.embree_config.empty()) c.argv.insert(c.argv.end(), {"--embree-config", a.embree_config});
  }
  std::printf("compare-builds: base %s, new %s, taking turns every %d timed frames\n",
              a.base_binary.c_str(), a.new_binary.c_str(), a.turn_block);
  std::fflush(stdout);
  const TurnsResult t = take_turns(commands[0], commands[1]);
  for (int i = 0; i < 2; ++i) {
    std::printf("%s: %s, %d turns, exit code %d\n", commands[i].label.c_str(), dirs[i].c_str(),
                t.turns[i], t.exit_code[i]);
    // 0: every job ok or skipped; 1: some failed, which compare judges.
    if (t.exit_code[i] != kExitOk && t.exit_code[i] != kExitJobsFailed) {
      std::fprintf(stderr, "shadowbench: the %s build's run failed (exit code %d)\n",
                   commands[i].label.c_str(), t.exit_code[i]);
      return t.exit_code[i] == kExitBadInput ? kExitBadInput : kExitInternal;
    }
  }
  Args compare = a;
  compare.positional = {dirs[0], dirs[1]};
  // Both runs timed the control next to every frame: their ratios are the
  // steadier measure (docs/ci.md, "What the gate catches").
  if (!a.normalize_given) compare.compare.normalize = "control";
  return cmd_compare(compare);
}

int cmd_scene(const Args& a) {
  const auto& p = a.positional;
  const std::string sub = p.empty() ? "" : p[0];
  if (sub == "export" && p.size() == 3) {
    const Scene s = build_scene_from_spec(p[1]);
    export_glb(s, p[2]);
    std::printf("%s: %zu meshes, %zu triangles, %zu textures\n", p[2].c_str(), s.meshes.size(),
                s.triangle_count(), s.textures.size());
    return kExitOk;
  }
  if (sub == "info" && p.size() == 2) {
    const std::string ext = std::filesystem::path(p[1]).extension().string();
    const bool file = ext == ".glb" || ext == ".gltf" || ext == ".GLB" || ext == ".GLTF";
    std::printf("%s", describe_scene(file ? load_gltf(p[1]) : build_scene_from_spec(p[1])).c_str());
    return kExitOk;
  }
  throw InputError(
      "", "command line",
      "expected 'scene export SCENE-SPEC OUT.glb' or 'scene info FILE'\n" + std::string(kUsage));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse_args(argc, argv);
    if ((!a.benchmark_out.empty() || !a.bencher_out.empty()) && a.command != "run" &&
        a.command != "report")
      throw InputError("", "command line",
                       "--benchmark-out and --bencher-out go with run or report");
    if ((!a.base_binary.empty() || !a.new_binary.empty()) && a.command != "compare-builds")
      throw InputError("", "command line", "--base and --new go with compare-builds");
    if (!a.take_turns.empty() && a.command != "run")
      throw InputError("", "command line", "--take-turns goes with run (compare-builds uses it)");
    if (a.turn_block_given && a.command != "run" && a.command != "compare-builds")
      throw InputError("", "command line", "--turn-block goes with run or compare-builds");
    if (a.compare_options_given && a.command != "compare" && a.command != "compare-builds")
      throw InputError("", "command line",
                       "--alpha, --time-threshold, --error-threshold, --timing and --normalize go "
                       "with compare or compare-builds");
    if (a.metric_given && a.command != "compare" && a.command != "compare-builds" &&
        a.command != "report")
      throw InputError("", "command line", "--metric goes with compare or report");
    if (a.command == "compare") return cmd_compare(a);
    if (a.command == "compare-builds") return cmd_compare_builds(a);
    if (a.command == "run") return cmd_run(a);
    if (a.command == "validate") return cmd_validate(a, false);
    if (a.command == "plan") return cmd_validate(a, true);
    if (a.command == "list") return cmd_list(a);
    if (a.command == "report") return cmd_report(a);
    if (a.command == "scene") return cmd_scene(a);
    if (a.command == "--help" || a.command == "help" || a.command == "-h") {
      std::printf("%s", kUsage);
      return kExitOk;
    }
    throw InputError("", "command line", "unknown command '" + a.command + "'\n" + kUsage);
  } catch (const InputError& e) {
    std::fprintf(stderr, "shadowbench: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadowbench: internal error: %s\n", e.what());
    return kExitInternal;
  }
}
