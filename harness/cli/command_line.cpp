#include "cli/command_line.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cli/technique_template.h"
#include "cli/version.h"
#include "core/error.h"
#include "gl/pass_timer.h"
#include "plan/shards.h"
#include "reference/embree_isa.h"

namespace sb::cli {

using core::kExitBadInput;
using plan::parse_shard;

namespace {

// Validators in the harness's words ("expected ..., found '...'"); CLI11
// prefixes the option's name. Empty descriptions: the help shows the
// option's type name alone.
CLI::Validator number_check() {
  return {[](std::string& text) -> std::string {
            size_t used = 0;
            try {
              (void)std::stod(text, &used);
            } catch (const std::exception&) {
              used = 0;
            }
            if (used == 0 || used != text.size()) return "expected a number, found '" + text + "'";
            return "";
          },
          ""};
}

// A number in [lo, hi] (a whole one when `whole`); else `what`, found '...'.
CLI::Validator bounded_check(double lo, double hi, bool whole, const std::string& what) {
  return {[lo, hi, whole, what](std::string& text) -> std::string {
            size_t used = 0;
            double v = NAN;
            try {
              v = std::stod(text, &used);
            } catch (const std::exception&) {
              used = 0;
            }
            if (used == 0 || used != text.size() || !(v >= lo && v <= hi) ||
                (whole && v != std::floor(v)))
              return what + ", found '" + text + "'";
            return "";
          },
          ""};
}

CLI::Validator whole_check(double lo, double hi, const std::string& what) {
  return bounded_check(lo, hi, true, what);
}

CLI::Validator choice_check(const std::vector<std::string>& choices) {
  return {[choices](std::string& text) -> std::string {
            for (const auto& c : choices)
              if (text == c) return "";
            std::string list;
            for (size_t i = 0; i < choices.size(); ++i)
              list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
            return "expected " + list + ", found '" + text + "'";
          },
          ""};
}

// "{a,b}": the help's type name of a choice, which the completion reads too.
std::string choice_type(const std::vector<std::string>& choices) {
  std::string t = "{";
  for (size_t i = 0; i < choices.size(); ++i) t += (i == 0 ? "" : ",") + choices[i];
  return t + "}";
}

CLI::Option* add_choice(CLI::App* sub, const std::string& name, std::string& value,
                        const std::vector<std::string>& choices, const std::string& doc) {
  return sub->add_option(name, value, doc)
      ->type_name(choice_type(choices))
      ->check(choice_check(choices));
}

void add_plugins(CLI::App* sub, Args& a) {
  sub->add_option("--plugins", a.plugins,
                  "load the technique plugins from DIR instead of the installed folder "
                  "($SHADOWBENCH_PLUGIN_PATH adds more)")
      ->type_name("DIR");
}

void add_max_jobs(CLI::App* sub, Args& a) {
  sub->add_option("--max-jobs", a.max_jobs,
                  "refuse configs that expand to more jobs (a guard against a typo in a sweep)")
      ->type_name("N")
      ->check(whole_check(1, 1e12, "expected a whole number in [1, 1e12]"));
}

void add_ci_outputs(CLI::App* sub, Args& a) {
  sub->add_option("--benchmark-out", a.benchmark_out,
                  "also write the timings as Google Benchmark JSON")
      ->type_name("FILE");
  sub->add_option("--bencher-out", a.bencher_out,
                  "also write timings and errors in Bencher Metric Format JSON")
      ->type_name("FILE");
}

void add_metric(CLI::App* sub, Args& a, const std::string& doc) {
  sub->add_option("--metric", a.compare.metric, doc)->type_name("PATH");
}

void add_turn_block(CLI::App* sub, Args& a) {
  sub->add_option("--turn-block", a.turn_block,
                  "timed frames per turn when two builds take turns (compare-builds)")
      ->type_name("N")
      ->check(whole_check(1, 100000, "expected a whole number of frames in [1, 100000]"));
}

void add_reference_options(CLI::App* sub, Args& a) {
  add_choice(sub, "--backend", a.backend, {"osmesa", "egl"},
             "the GL backend: OSMesa (llvmpipe, anywhere) or EGL (a GPU if there is one)");
  sub->add_option("--cache-dir", a.cache_dir,
                  "where reference renders are cached, keyed by everything they depend on")
      ->type_name("DIR");
  sub->add_flag("--no-cache", a.no_cache, "compute every reference afresh, and store none");
  sub->add_option("--embree-config", a.embree_config,
                  "pin the reference's Embree ISA, e.g. isa=avx2 or max_isa=avx2 "
                  "(default: the best the CPU has)")
      ->type_name("CFG")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            try {
              reference::check_embree_config(text);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return "";
          },
          ""));
}

// compare's options, shared by compare-builds.
void add_compare_options(CLI::App* sub, Args& a, std::string& normalize) {
  sub->add_option("--alpha", a.compare.alpha,
                  "significance level of the Mann-Whitney U test on the frame times")
      ->type_name("A")
      ->check(number_check());
  sub->add_option("--time-threshold", a.compare.time_threshold,
                  "flag a slower median only beyond this relative change (0.10 is 10 %)")
      ->type_name("R")
      ->check(number_check());
  sub->add_option("--error-threshold", a.compare.error_threshold,
                  "flag a larger error only beyond this absolute change")
      ->type_name("E")
      ->check(number_check());
  add_metric(
      sub, a,
      "the error compared: <visibility|shaded>.<geometry|all|penumbra|soft_union|...>.<key>, "
      "or none (times only)");
  add_choice(sub, "--timing", a.compare.timing, {"frame", "technique", "none"},
             "which times: whole frames, the technique's passes, or none (errors only)");
  add_choice(sub, "--normalize", normalize, {"none", "control"},
             "compare absolute times (same host only) or each frame's ratio to the control job's");
  add_choice(sub, "--correction", a.compare.correction, {"holm", "bh", "none"},
             "share alpha across the jobs tested: Holm (family-wise), Benjamini-Hochberg, or "
             "none (alpha per job)");
  sub->add_flag("--allow-reference-change", a.compare.allow_reference_change,
                "compare errors also where BASE and NEW used different references (noted)");
}

// A positional argument: its name is its placeholder, so no type name.
template <class T>
void add_argument(CLI::App* sub, const std::string& name, T& value, const std::string& doc) {
  sub->add_option(name, value, doc)->type_name("");
}

// --help-all (and so the man page help2man makes from it): each command
// under a heading of its own, "shadowbench run:", at the first column, then
// its description and its arguments and options indented, with no group
// headings of their own, so help2man sets one subsection per command.
class ExpandedFormatter : public CLI::Formatter {
 public:
  std::string make_expanded(const CLI::App* sub) const override {
    std::string body = make_positionals(sub) + make_groups(sub, CLI::AppFormatMode::Sub);
    std::string options;
    size_t start = 0;
    while (start < body.size()) {
      const size_t end = std::min(body.find('\n', start), body.size());
      const std::string line = body.substr(start, end - start);
      const bool heading = !line.empty() && line[0] != ' ' && line.back() == ':';
      if (!line.empty() && !heading) options += "  " + line + "\n";
      start = end + 1;
    }
    std::string out =
        "\nshadowbench " + command_path(*sub) + ":\n  " + sub->get_description() + "\n\n" + options;
    for (const CLI::App* c : sub->get_subcommands({})) out += make_expanded(c);
    return out;
  }

  std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const override {
    if (mode != CLI::AppFormatMode::All) return CLI::Formatter::make_subcommands(app, mode);
    std::string out;
    for (const CLI::App* c : app->get_subcommands({})) out += make_expanded(c);
    return out;
  }
};

CLI::App* add_command(CLI::App& app, const std::string& name, const std::string& description,
                      const std::string& example) {
  CLI::App* sub = app.add_subcommand(name, description);
  sub->group("Commands");
  sub->footer("Example:\n  " + example);
  // Unknown options are collected and reported by parse_command_line, which
  // can say which other command takes them.
  sub->allow_extras();
  return sub;
}

// The options of every command but `from`, as "--alpha" -> "compare, compare-builds".
std::string commands_taking(CLI::App& app, const std::string& option, const CLI::App* from) {
  std::vector<std::string> takers;
  for (CLI::App* c : all_commands(app)) {
    if (c == from) continue;
    for (const CLI::Option* o : c->get_options())
      if (!o->get_lnames().empty() && "--" + o->get_lnames()[0] == option &&
          !o->get_group().empty())
        takers.push_back(command_path(*c));
  }
  std::string text;
  for (size_t i = 0; i < takers.size(); ++i)
    text += (i == 0 ? "" : i + 1 == takers.size() ? " or " : ", ") + takers[i];
  return text;
}

}  // namespace

std::string command_path(const CLI::App& command) {
  std::vector<std::string> names = {command.get_name()};
  for (const CLI::App* p = command.get_parent(); p != nullptr && p->get_parent() != nullptr;
       p = p->get_parent())
    names.insert(names.begin(), p->get_name());
  std::string path;
  for (const std::string& n : names) path += (path.empty() ? "" : " ") + n;
  return path;
}

std::vector<CLI::App*> all_commands(CLI::App& app) {
  std::vector<CLI::App*> out;
  for (CLI::App* c : app.get_subcommands(nullptr)) {
    out.push_back(c);
    for (CLI::App* d : all_commands(*c)) out.push_back(d);
  }
  return out;
}

void AppDeleter::operator()(CLI::App* app) const { delete app; }

AppPtr make_command_line(Args& a) {
  AppPtr app(new CLI::App(
      "shadowbench: a headless batch benchmark of shadow-rendering techniques. It renders every "
      "technique variant of a JSON experiment at every resolution, times each pass, and "
      "measures each one against a ray-traced reference.",
      "shadowbench"));
  app->name("shadowbench");
  app->option_defaults()->always_capture_default();
  app->set_help_flag("-h,--help", "print this help and exit");
  app->formatter(std::make_shared<ExpandedFormatter>());
  app->get_formatter()->column_width(34);
  app->require_subcommand(1);
  app->allow_extras();
  app->set_help_all_flag("--help-all", "print the help of every command");
  app->set_version_flag("--version", version_text,
                        "print the version, git describe, the GL backends built and the "
                        "folders plugins and data are found in");
  app->footer(
      "`shadowbench COMMAND --help` prints a command's options.\n"
      "Exit codes: 0 every job ok or skipped, 1 some job failed (the others' results are kept), "
      "2 bad input or usage (the message names the file and the place in it, or the option), "
      "3 environment (no GL context, no plugins, run folder in use; validate and plan: a plugin "
      "CONFIG needs failed to load), 4 compare found a regression.");

  CLI::App* run = add_command(*app, "run",
                              "Render every job of CONFIG, time it, measure it against the "
                              "reference, and write records, tables and images. Rerun to resume.",
                              "shadowbench run configs/quick.json --out results/quick");
  add_argument(run, "CONFIG", a.config, "the experiment (JSON)");
  run->add_option("--out", a.out, "the run folder (default: results/<name>-<UTC time>)")
      ->type_name("DIR");
  add_reference_options(run, a);
  run->add_flag("--no-images", a.no_images, "write no EXR/PNG images (records and tables only)");
  run->add_flag("--gbuffer", a.gbuffer, "also write each job's G-buffer positions (EXR)");
  add_plugins(run, a);
  run->add_flag("--quiet", a.quiet, "no progress line and no table at the end");
  add_ci_outputs(run, a);
  add_max_jobs(run, a);
  add_choice(run, "--pass-timing", a.pass_timing, {"coarse", "fine"},
             "fine: extra frames with every pass in its own timing bracket");
  add_turn_block(run, a);
  add_choice(run, "--isolation", a.isolation, {"group", "job", "none"},
             "where jobs render: a child process per (scene, resolution), one per job, or this "
             "process (then a crash or a hang ends the run)");
  run->add_option("--job-timeout", a.job_timeout,
                  "kill a job that runs longer and record it as failed (default: the config's "
                  "limits.job_seconds, 1800); needs isolation")
      ->type_name("SECONDS")
      ->check(bounded_check(1, 604800, false, "expected a number of seconds in [1, 604800]"));
  run->add_option("--shard", a.shard,
                  "run only shard K of N (1 <= K <= N), in the layout `plan` prints; merge the N "
                  "run folders with `merge`")
      ->type_name("K/N")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            try {
              (void)parse_shard(text);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return "";
          },
          ""));
  run->add_option("--take-turns", a.take_turns, "IN_FD,OUT_FD of compare-builds' turn pipes")
      ->group("");  // internal: compare-builds runs both builds with it

  for (const bool plan : {false, true}) {
    CLI::App* sub =
        plan ? add_command(*app, "plan",
                           "List every job of CONFIG: to run, or skipped and why. No GL is used.",
                           "shadowbench plan configs/scenes.json")
             : add_command(*app, "validate",
                           "Check CONFIG and its scenes without rendering: exit 2 naming the "
                           "file and JSON pointer of the first error.",
                           "shadowbench validate configs/forest06-spheres.json");
    add_argument(sub, "CONFIG", a.config, "the experiment (JSON)");
    add_plugins(sub, a);
    add_max_jobs(sub, a);
    if (plan)
      sub->add_option("--shards", a.shards,
                      "also lay the jobs out in N shards balanced by estimated cost, as `run` "
                      "runs them one by one")
          ->type_name("N")
          ->check(whole_check(1, 10000, "expected a whole number of shards in [1, 10000]"));
    if (plan)
      sub->add_flag("--json", a.plan_json,
                    "print the plan as JSON instead (every job's outcome, cost and shard; the "
                    "plan.json `run` writes, docs/results.md)");
  }

  CLI::App* merge = add_command(
      *app, "merge",
      "Merge the run folders of one config's shards into OUT: records, images and reports. "
      "Refuses timings from different hosts or GL renderers unless told.",
      "shadowbench merge results/sweep results/sweep-1 results/sweep-2");
  add_argument(merge, "OUT", a.out, "the merged run folder (new, or empty)");
  merge->get_option("OUT")->required();
  add_argument(merge, "DIR", a.merge_dirs, "the run folders to merge");
  merge->get_option("DIR")->required()->default_str("");
  merge->add_flag("--allow-mixed-hosts", a.allow_mixed_hosts,
                  "merge timings from different hosts or GL renderers; the report marks them");

  CLI::App* list = add_command(
      *app, "list",
      "List the techniques (with their family, needs and parameters), the needs and the scene "
      "types; or only the NAMEs given.",
      "shadowbench list pcss sphere_grid");
  add_argument(list, "NAME", a.names, "techniques or scene types to show");
  list->get_option("NAME")->default_str("");  // not "[]"
  add_plugins(list, a);
  list->add_flag("--markdown", a.markdown,
                 "print docs/parameters.md: every parameter as Markdown tables");
  list->add_flag("--record-schema", a.record_schema,
                 "print the job record's schema tables, as docs/results.md holds them");
  list->add_flag("--plan-schema", a.plan_schema,
                 "print plan.json's schema tables, as docs/results.md holds them");
  list->add_flag("--names", a.names_only,
                 "print technique and scene type names only, one per line");

  CLI::App* report = add_command(
      *app, "report",
      "Write the tables (CSV, Markdown), the charts (SVG, PNG) and an offline index.html of "
      "a run folder.",
      "shadowbench report results/quick --metric visibility.penumbra.rmse");
  add_argument(report, "RUN_DIR", a.run_dir, "a folder `run` wrote");
  report->add_option("--out", a.out, "where charts and index.html go (default: RUN_DIR/report)")
      ->type_name("DIR");
  add_metric(report, a, "the error on the charts' y axis");
  report->add_flag("--no-viewer-data", a.no_viewer_data,
                   "no data files for the image viewer (about 5.3 bytes per pixel per image): it "
                   "then shows the PNGs, without V, error or pixel values");
  CLI::Option* latex = report->add_flag(
      "--latex", a.latex,
      "also write booktabs tables and pgfplots CSVs of error against time into OUT/latex, "
      "with tables.tex showing them all (docs/paper.md)");
  report
      ->add_option("--latex-columns", a.latex_columns,
                   "the tables' columns after the technique, comma-separated report columns "
                   "(default: frame_ms,x_control,rmse,penumbra_rmse,ssim,flip, those with values)")
      ->type_name("COLS")
      ->delimiter(',')
      ->default_str("")  // not "[]"
      ->needs(latex);
  add_choice(report, "--style", a.chart_style, {"default", "paper"},
             "the charts' style: paper draws them 3.3 in wide in Computer Modern, as PDF too");
  add_ci_outputs(report, a);

  CLI::App* compare = add_command(
      *app, "compare",
      "Compare two run folders job by job: exit 4 when a job got significantly slower or less "
      "accurate beyond the thresholds.",
      "shadowbench compare results/baselines/ci results/ci-new --normalize control");
  add_argument(compare, "BASE_DIR", a.base_dir, "the baseline run folder");
  add_argument(compare, "NEW_DIR", a.new_dir, "the run folder to judge");
  add_compare_options(compare, a, a.compare.normalize);

  CLI::App* builds = add_command(
      *app, "compare-builds",
      "Run CONFIG with two shadowbench builds taking turns, block of frames by block of "
      "frames, then compare them (the A/B gate for pull requests, docs/ci.md).",
      "shadowbench compare-builds --base ../base/build/shadowbench --new build/shadowbench "
      "configs/ci.json");
  add_argument(builds, "CONFIG", a.config, "the experiment (JSON) both builds run");
  builds->add_option("--base", a.base_binary, "the baseline build's shadowbench")->type_name("BIN");
  builds->add_option("--new", a.new_binary, "the new build's shadowbench")->type_name("BIN");
  builds
      ->add_option("--out", a.out,
                   "where the two runs go, as DIR/base and DIR/new "
                   "(default: results/compare-builds-<UTC time>)")
      ->type_name("DIR");
  add_turn_block(builds, a);
  add_reference_options(builds, a);
  add_compare_options(builds, a, a.builds_normalize);

  CLI::App* scene = add_command(*app, "scene", "Export a generated scene, or describe a scene.",
                                "shadowbench scene info configs/models/jeep.glb");
  scene->require_subcommand(1);
  CLI::App* scene_export =
      add_command(*scene, "export", "Write a generated scene as a binary glTF file.",
                  "shadowbench scene export sphere_grid:grid=3,light_size=2 grid.glb");
  add_argument(scene_export, "SCENE-SPEC", a.scene_spec,
               "TYPE:key=value,... or a JSON object {\"type\": ..., \"params\": {...}}");
  add_argument(scene_export, "OUT", a.scene_out, "the .glb file to write");
  CLI::App* scene_info =
      add_command(*scene, "info", "Describe a scene: meshes, triangles, materials, light, bounds.",
                  "shadowbench scene info configs/models/jeep.glb");
  add_argument(scene_info, "SCENE", a.scene_spec, "a .glb or .gltf file, or a SCENE-SPEC");

  CLI::App* history = add_command(
      *app, "history",
      "Keep runs across commits in one SQLite file (add), and report every job's time and "
      "error across them with the commits where they stepped (report).",
      "shadowbench history add results/ci-20261206-120000");
  history->require_subcommand(1);
  CLI::App* history_add = add_command(
      *history, "add",
      "Store RUN_DIR's records at a commit: every job's times (absolute, and as a ratio to the "
      "control job) and errors, with the host and build fingerprints. Adding a run again at "
      "the same commit replaces it.",
      "shadowbench history add results/ci-20261206-120000 --commit $(git rev-parse HEAD)");
  add_argument(history_add, "RUN_DIR", a.run_dir, "a folder `run` or `merge` wrote");
  history_add->get_option("RUN_DIR")->required();
  history_add
      ->add_option("--commit", a.commit,
                   "the commit the run was built from (default: `git rev-parse HEAD` in the "
                   "current folder)")
      ->type_name("SHA");
  history_add->add_option("--db", a.history_db, "the history file, created when absent")
      ->type_name("FILE")
      ->capture_default_str();
  CLI::App* history_report = add_command(
      *history, "report",
      "Write a static, offline site of the history into --out: every series' latest time and "
      "error with a sparkline, the steps found in them (change points, with the commit), and "
      "a page per series with its charts and the runs on either side of each step; the steps "
      "also as steps.json.",
      "shadowbench history report --db results/history.sqlite --out results/history");
  history_report->add_option("--db", a.history_db, "the history file")
      ->type_name("FILE")
      ->capture_default_str();
  history_report->add_option("--out", a.out, "the site's folder (default: results/history)")
      ->type_name("DIR");
  add_choice(history_report, "--time", a.history_time, {"ratio", "frame_ms", "technique_ms"},
             "the time plotted: the frame's time over the control's next to it (comparable "
             "across hosts), or this host's milliseconds of the frame or the technique");
  add_metric(history_report, a, "the error plotted: a path into a record's metrics");

  CLI::App* new_technique = add_command(
      *app, "new-technique",
      "Write a plugin folder for a new technique NAME: its source (a working shadow map with PCF "
      "to start from), CMakeLists.txt, a config that runs it beside its nearest built-ins, and a "
      "README with the commands to build, load and run it.",
      "shadowbench new-technique my_pcf --dir ~/my_pcf");
  add_argument(new_technique, "NAME", a.new_name,
               "the technique's name: a lowercase C identifier no plugin uses");
  new_technique->get_option("NAME")->required();
  std::vector<std::string> families;
  std::string family_doc = "the template:";
  for (const TechniqueTemplate& t : technique_templates()) {
    families.push_back(t.family);
    family_doc += (families.size() == 1 ? " " : "; ") + t.family + ", " + t.summary;
  }
  add_choice(new_technique, "--family", a.family, families, family_doc);
  new_technique
      ->add_option("--dir", a.dir, "the folder to write, which must not exist (default: NAME)")
      ->type_name("DIR");
  add_plugins(new_technique, a);

  CLI::App* help = add_command(*app, "help", "Print the help of a command, or of all of them.",
                               "shadowbench help compare");
  add_argument(help, "COMMAND", a.names, "a command, e.g. run or scene export");
  help->get_option("COMMAND")->default_str("");
  help->add_flag("--markdown", a.markdown, "print docs/cli.md: every command's options");

  CLI::App* completion = add_command(
      *app, "completion", "Print a shell completion script (bash).",
      "shadowbench completion bash > ~/.local/share/bash-completion/completions/shadowbench");
  completion->add_option("SHELL", a.shell, "the shell")->type_name("{bash}");
  return app;
}

int parse_command_line(CLI::App& app, int argc, const char* const* argv, Args& a) {
  auto usage_error = [](const std::string& message, const std::string& hint) {
    std::fprintf(stderr, "shadowbench: error: %s\n%s\n", message.c_str(), hint.c_str());
    return int(kExitBadInput);
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The deepest command named so far says where to look.
    CLI::App* deepest = &app;
    while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
    const std::string where =
        deepest == &app ? "shadowbench" : "shadowbench " + command_path(*deepest);
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr &&
        deepest->get_require_subcommand_min() > 0) {
      // A command without its subcommand: name what was given instead, and
      // say which there are.
      std::string choices;
      for (const CLI::App* c : deepest->get_subcommands(nullptr))
        choices += (choices.empty() ? "" : ", ") + c->get_name();
      const std::vector<std::string> extra = deepest->remaining();
      const std::string what = deepest == &app ? "command" : command_path(*deepest) + " command";
      if (!extra.empty() && extra.front().rfind('-', 0) == 0)
        return usage_error(
            "unknown option '" + extra.front() + "'; expected a " + what + " (" + choices + ")",
            "(see " + where + " --help)");
      return usage_error(
          (extra.empty() ? "expected a " + what : "unknown " + what + " '" + extra.front() + "'") +
              " (" + choices + ")",
          "(see " + where + " --help)");
    }
    return usage_error(e.what(), "(see " + where + " --help)");
  }
  CLI::App* command = &app;
  while (!command->get_subcommands().empty()) command = command->get_subcommands().front();
  // Arguments no command took: an unknown option, a misplaced one, or one
  // argument too many. The deepest command with one is named.
  CLI::App* with_extra = command;
  while (with_extra != nullptr && with_extra->remaining().empty())
    with_extra = with_extra->get_parent();
  if (with_extra != nullptr) {
    const std::string arg = with_extra->remaining().front();
    const std::string name = with_extra == &app ? std::string() : command_path(*with_extra);
    const std::string hint = "(see shadowbench " + (name.empty() ? "" : name + " ") + "--help)";
    if (arg.rfind('-', 0) != 0) {
      if (with_extra == &app) return usage_error("unknown command '" + arg + "'", hint);
      return usage_error("unexpected argument '" + arg + "' for " + name, hint);
    }
    const std::string option = arg.substr(0, arg.find('='));
    if (const std::string takers = commands_taking(app, option, with_extra); !takers.empty())
      return usage_error(option + " goes with " + takers + ", not with " + name, hint);
    return usage_error("unknown option '" + option + "'" + (name.empty() ? "" : " for " + name),
                       hint);
  }
  a.command = command_path(*command);
  return -1;
}

}  // namespace sb::cli
