#pragma once
// The timing control (config `frames.control`, `none` by default) is a
// baseline, not a competitor: every job's frames are timed next to its
// frames, and the records name it (timing.control.technique). Pareto fronts
// (charts, pgfplots CSVs), rankings and the paper tables' bold leave it out;
// it may still be drawn, labelled as the control, as a reference.
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// Whether `r` is the control of a job of `group` (`r`'s own record included:
// the control job is its own control).
bool is_control(const std::vector<const record::JobRecord*>& group, const record::JobRecord& r);

}  // namespace sb::results
