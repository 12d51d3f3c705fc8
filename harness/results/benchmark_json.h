#pragma once
// Google Benchmark JSON (`--benchmark-out FILE`), as benchmark 1.7 writes it
// with --benchmark_repetitions, so that its tools (compare.py,
// github-action-benchmark's "googlecpp" parser) read our runs:
//   context     date, host_name, executable, num_cpus, mhz_per_cpu,
//               cpu_scaling_enabled, caches (empty), load_avg,
//               library_build_type, json_schema_version (1, as 1.8+ writes)
//   benchmarks  for every ok job, `<job_id>/frame` and `<job_id>/pass:<name>`
//               (in pass order): one "iteration" entry per timed frame
//               (repetition), then the "aggregate" entries mean, median,
//               stddev and cv, as benchmark does. Times are in ms; cpu_time
//               equals real_time (the harness measures wall time only).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// The context block for this machine and process, now.
nlohmann::json benchmark_context();
nlohmann::json make_benchmark_json(const std::vector<record::JobRecord>& records,
                                   const nlohmann::json& context);
// Writes make_benchmark_json(records, benchmark_context()) atomically.
void write_benchmark_json(const std::string& path, const std::vector<record::JobRecord>& records);

}  // namespace sb::results
