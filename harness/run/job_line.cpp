#include "run/job_line.h"

#include <cstdio>

#include "results/noisy_jobs.h"
#include "results/report_columns.h"

namespace sb::run {

using record::JobRecord;
using record::JobStatus;
using record::to_string;
using results::report_column;

std::string job_line(const JobRecord& record, size_t done, size_t total) {
  std::string line = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " +
                     record.scene_variant + " @ " + record.resolution + "  " +
                     record.technique_variant + ": " + to_string(record.status);
  if (record.status == JobStatus::Ok && record.timing && record.metrics) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "  frame %.2f ms, technique %.2f ms",
                  record.timing->frame.median, record.timing->technique.median);
    line += buf;
    // The very cell the tables show (empty for a NaN, or a record without
    // the geometry region).
    const std::string rmse = report_column("rmse").cell(record);
    if (!rmse.empty()) line += ", geometry RMSE " + rmse;
    if (const auto& chosen = record.timing->auto_frames)
      line += ", " + std::to_string(record.timing->timed_frames) + " frames (" +
              (chosen->stop == "target" ? std::string("interval within target")
                                        : chosen->stop + " reached") +
              ")";
    if (record.session && record.session->retimed_from) line += " (re-timed; errors kept)";
    // The same words as the tables' mark (results/noisy_jobs.h).
    if (const auto noisy = results::noisy_label(record)) line += "  " + *noisy;
  } else if (record.status != JobStatus::Ok) {
    line += " (" + record.reason.value_or("") + ")";
  }
  return line;
}

}  // namespace sb::run
