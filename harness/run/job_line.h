#pragma once
// The console's line for a finished job, e.g.
// "[3/20] sphere_grid @ 320x240  pcss: ok  frame 1.23 ms, technique 0.45 ms, geometry RMSE
// 0.03727  noisy ±7.2 %". Its error is the tables' headline: the `rmse` column of results.csv and
// summary.md (the visibility over the `geometry` region, docs/results.md "Regions"), printed as the
// tables print it; a noisy job (record timing.noise) says so, with its median's interval.
#include <cstddef>
#include <string>

#include "record/job_record.h"

namespace sb::run {

std::string job_line(const record::JobRecord& record, size_t done, size_t total);

}  // namespace sb::run
