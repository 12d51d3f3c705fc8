#include "cli/options.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "reference/embree_isa.h"

namespace sb::cli {

namespace {

// A number in [lo, hi] (a whole one when `whole`); else `what`, found '...'.
CLI::Validator range_check(double lo, double hi, bool whole, const std::string& what) {
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

// "{a,b}": the help's type name of a choice.
std::string choice_type(const std::vector<std::string>& choices) {
  std::string t = "{";
  for (size_t i = 0; i < choices.size(); ++i) t += (i == 0 ? "" : ",") + choices[i];
  return t + "}";
}

}  // namespace

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

CLI::Validator bounded_check(double lo, double hi, const std::string& what) {
  return range_check(lo, hi, false, what);
}

CLI::Validator whole_check(double lo, double hi, const std::string& what) {
  return range_check(lo, hi, true, what);
}

CLI::Validator parser_check(std::function<void(const std::string&)> check) {
  return {[check = std::move(check)](std::string& text) -> std::string {
            try {
              check(text);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return "";
          },
          ""};
}

CLI::Option* add_choice(CLI::App* sub, const std::string& name, std::string& value,
                        const std::vector<std::string>& choices, const std::string& doc) {
  return sub->add_option(name, value, doc)
      ->type_name(choice_type(choices))
      ->check(choice_check(choices));
}

void add_plugins(CLI::App* sub, std::string& plugins) {
  sub->add_option("--plugins", plugins,
                  "load the technique plugins from DIR instead of the installed folder "
                  "($SHADOWBENCH_PLUGIN_PATH adds more)")
      ->type_name("DIR");
}

void add_max_jobs(CLI::App* sub, double& max_jobs) {
  sub->add_option("--max-jobs", max_jobs,
                  "refuse configs that expand to more jobs (a guard against a typo in a sweep)")
      ->type_name("N")
      ->check(whole_check(1, 1e12, "expected a whole number in [1, 1e12]"));
}

void add_ci_outputs(CLI::App* sub, CiOutputs& outputs) {
  sub->add_option("--benchmark-out", outputs.benchmark_out,
                  "also write the timings as Google Benchmark JSON")
      ->type_name("FILE");
  sub->add_option("--bencher-out", outputs.bencher_out,
                  "also write timings and errors in Bencher Metric Format JSON")
      ->type_name("FILE");
}

void add_reference_options(CLI::App* sub, ReferenceArgs& reference) {
  add_choice(sub, "--backend", reference.backend, {"osmesa", "egl"},
             "the GL backend: OSMesa (llvmpipe, anywhere) or EGL (a GPU if there is one)");
  sub->add_option("--cache-dir", reference.cache_dir,
                  "where reference renders are cached, keyed by everything they depend on")
      ->type_name("DIR");
  sub->add_flag("--no-cache", reference.no_cache, "compute every reference afresh, and store none");
  sub->add_option("--embree-config", reference.embree_config,
                  "pin the reference's Embree ISA, e.g. isa=avx2 or max_isa=avx2 "
                  "(default: the best the CPU has)")
      ->type_name("CFG")
      ->check(parser_check(reference::check_embree_config));
}

void add_turn_block(CLI::App* sub, int& turn_block) {
  sub->add_option("--turn-block", turn_block,
                  "timed frames per turn when two builds take turns (compare-builds)")
      ->type_name("N")
      ->check(whole_check(1, 100000, "expected a whole number of frames in [1, 100000]"));
}

void add_metric(CLI::App* sub, std::string& metric, const std::string& doc) {
  sub->add_option("--metric", metric, doc)->type_name("PATH");
}

CLI::Option* add_only(CLI::App* sub, std::vector<std::string>& patterns, const std::string& doc) {
  // One pattern per --only, so that it never takes the CONFIG after it.
  return sub->add_option("--only", patterns, doc)
      ->type_name("PATTERN")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

}  // namespace sb::cli
