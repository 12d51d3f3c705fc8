#include "cli/shared.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "config/map_sizes.h"
#include "config/unread_params.h"
#include "core/error.h"
#include "core/install_layout.h"
#include "results/bencher_json.h"
#include "results/benchmark_json.h"

namespace sb::cli {

using config::Experiment;
using config::ExperimentLimits;
using config::load_experiment;
using config::unequal_map_size_warnings;
using config::unread_parameter_warnings;
using core::default_plugin_dir;
using core::doc_path;
using core::extra_plugin_dirs;
using core::InputError;
using core::kExitInternal;
using plugin::PluginLoadFailure;
using plugin::Registry;
using record::JobRecord;
using results::write_bencher_json;
using results::write_benchmark_json;

namespace {

// A folder in the plugin path that holds no module at all is most likely a
// wrong path (a build folder instead of its plugin folder, say).
bool holds_no_plugin(const std::string& dir) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".so") return false;
  return !ec;
}

}  // namespace

Registry load_registry(const std::string& plugins) {
  Registry r;
  std::vector<std::string> dirs = {plugins.empty() ? default_plugin_dir() : plugins};
  for (const std::string& dir : extra_plugin_dirs()) dirs.push_back(dir);
  int from_path = 0;  // modules loaded from $SHADOWBENCH_PLUGIN_PATH
  try {
    for (size_t i = 0; i < dirs.size(); ++i) {
      const char* origin = i == 0 ? "" : " (from $SHADOWBENCH_PLUGIN_PATH)";
      try {
        const int loaded = r.load_plugins(dirs[i]);
        if (i > 0) from_path += loaded;
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string(e.what()) + origin);
      }
      if (holds_no_plugin(dirs[i]))
        std::fprintf(stderr, "shadowbench: warning: plugin folder %s%s holds no plugin (*.so)\n",
                     dirs[i].c_str(), origin);
    }
    // A module that failed is said by every command; only jobs naming a
    // technique it might have registered fail (config/unknown_technique.h).
    for (const PluginLoadFailure& f : r.load_failures())
      std::fprintf(stderr, "shadowbench: warning: plugin %s failed to load: %s\n", f.file.c_str(),
                   f.message.c_str());
    if (r.all().empty()) {
      std::string where;
      for (const std::string& d : dirs) where += (where.empty() ? "" : ", ") + d;
      throw std::runtime_error("no technique plugins in " + where);
    }
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "shadowbench: %s\n", e.what());
    std::exit(kExitInternal);
  }
  // For an unknown technique: perhaps its plugin was never looked for.
  if (dirs.size() == 1) {
    r.set_search_hint("$SHADOWBENCH_PLUGIN_PATH is not set: only the plugins in " + dirs[0] +
                      " were loaded (" + doc_path("install.md") + ", \"Plugin folders\")");
  } else if (from_path == 0) {
    std::string path;
    for (size_t i = 1; i < dirs.size(); ++i) path += (i == 1 ? "" : ":") + dirs[i];
    r.set_search_hint("$SHADOWBENCH_PLUGIN_PATH (" + path + ") loaded no plugin");
  }
  return r;
}

std::string one_config(const std::string& config, const std::string& command) {
  if (config.empty())
    throw InputError("", "command line",
                     "expected exactly one CONFIG file (see shadowbench " + command + " --help)");
  return config;
}

Experiment load_checked_experiment(const ExperimentArgs& a, const Registry& r) {
  ExperimentLimits limits;
  limits.max_jobs = uint64_t(a.max_jobs);
  Experiment e = load_experiment(one_config(a.config, a.command), r, limits);
  for (const std::string& w : unread_parameter_warnings(e))
    std::fprintf(stderr, "shadowbench: warning: %s\n", w.c_str());
  for (const std::string& w : unequal_map_size_warnings(e))
    std::fprintf(stderr, "shadowbench: warning: %s\n", w.c_str());
  return e;
}

std::string default_run_id(const std::string& name) {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", &tm);
  return name + "-" + buf;
}

void write_ci_outputs(const CiOutputs& outputs, const std::vector<JobRecord>& records) {
  if (!outputs.benchmark_out.empty()) {
    write_benchmark_json(outputs.benchmark_out, records);
    std::printf("Google Benchmark JSON: %s\n", outputs.benchmark_out.c_str());
  }
  if (!outputs.bencher_out.empty()) {
    write_bencher_json(outputs.bencher_out, records);
    std::printf("Bencher Metric Format JSON: %s\n", outputs.bencher_out.c_str());
  }
}

}  // namespace sb::cli
