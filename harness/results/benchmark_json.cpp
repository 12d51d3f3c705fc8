#include "results/benchmark_json.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <numeric>

#include "core/atomic_file.h"
#include "store/results_store.h"

namespace sb::results {

using core::write_file_atomically;
using record::JobRecord;
using record::JobStatus;
using store::json_text;

namespace {

using nlohmann::json;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// One benchmark: its repetitions, then benchmark's aggregates (only with two
// or more repetitions, as benchmark itself does). stddev is the sample
// standard deviation and cv = stddev / mean, as in benchmark's statistics.cc.
void add_benchmark(json& out, const std::string& name, int family, const std::vector<double>& s) {
  if (s.empty()) return;
  const auto reps = int(s.size());
  auto entry = [&](const std::string& entry_name, const char* run_type) {
    json e;
    e["name"] = entry_name;
    e["family_index"] = family;
    e["per_family_instance_index"] = 0;
    e["run_name"] = name;
    e["run_type"] = run_type;
    e["repetitions"] = reps;
    return e;
  };
  for (int i = 0; i < reps; ++i) {
    json e = entry(name, "iteration");
    e["repetition_index"] = i;
    e["threads"] = 1;
    e["iterations"] = 1;
    e["real_time"] = s[size_t(i)];
    e["cpu_time"] = s[size_t(i)];
    e["time_unit"] = "ms";
    out.push_back(std::move(e));
  }
  if (reps < 2) return;
  const double n = double(reps);
  const double mean = std::accumulate(s.begin(), s.end(), 0.0) / n;
  double ss = 0;
  for (double v : s) ss += (v - mean) * (v - mean);
  const double stddev = std::sqrt(ss / (n - 1));
  const double cv = mean != 0 ? stddev / mean : 0;
  const std::pair<const char*, double> aggregates[] = {
      {"mean", mean}, {"median", median(s)}, {"stddev", stddev}, {"cv", cv}};
  for (const auto& [agg, value] : aggregates) {
    json e = entry(name + "_" + agg, "aggregate");
    e["threads"] = 1;
    e["aggregate_name"] = agg;
    e["aggregate_unit"] = std::string(agg) == "cv" ? "percentage" : "time";
    e["iterations"] = reps;
    e["real_time"] = value;
    e["cpu_time"] = value;
    e["time_unit"] = "ms";
    out.push_back(std::move(e));
  }
}

int cpu_mhz() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("cpu MHz", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    return int(std::lround(std::strtod(line.c_str() + colon + 1, nullptr)));
  }
  return 0;
}

}  // namespace

json benchmark_context() {
  json c;
  char date[64];
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S+00:00", &tm);
  c["date"] = date;
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  c["host_name"] = host;
  c["executable"] = "shadowbench";
  c["num_cpus"] = std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
  c["mhz_per_cpu"] = cpu_mhz();
  c["cpu_scaling_enabled"] = false;
  c["caches"] = json::array();
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3)
    c["load_avg"] = {load[0], load[1], load[2]};
  else
    c["load_avg"] = json::array();
#ifdef NDEBUG
  c["library_build_type"] = "release";
#else
  c["library_build_type"] = "debug";
#endif
  c["json_schema_version"] = 1;
  return c;
}

json make_benchmark_json(const std::vector<JobRecord>& records, const json& context) {
  json out;
  out["context"] = context;
  for (const auto& r : records) {
    if (r.status != JobStatus::Ok) continue;
    for (const auto& [key, value] : {std::pair<const char*, const std::string&>{"run_id", r.run_id},
                                     {"experiment", r.experiment},
                                     {"backend", r.backend},
                                     {"gl_renderer", r.gl_renderer},
                                     {"timing_source", r.timing_source}})
      if (!out["context"].contains(std::string("shadowbench_") + key))
        out["context"][std::string("shadowbench_") + key] = value;
    break;
  }
  json benchmarks = json::array();
  int family = 0;
  for (const auto& r : records) {
    if (r.status != JobStatus::Ok || !r.timing) continue;
    add_benchmark(benchmarks, r.job_id + "/frame", family++, r.timing->frame.samples);
    if (!r.timing->fine) continue;
    // In pass order (which names every pass).
    for (const auto& name : r.timing->fine->pass_order)
      add_benchmark(benchmarks, r.job_id + "/pass:" + name, family++,
                    r.timing->fine->passes.at(name).samples);
  }
  out["benchmarks"] = std::move(benchmarks);
  return out;
}

void write_benchmark_json(const std::string& path, const std::vector<JobRecord>& records) {
  write_file_atomically(path,
                        json_text(make_benchmark_json(records, benchmark_context()), 2) + "\n");
}

}  // namespace sb::results
