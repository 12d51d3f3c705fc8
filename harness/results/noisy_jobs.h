#pragma once
// Noisy jobs said out loud (record timing.noise; config
// `frames.noise_threshold`; docs/results.md, "Noise"): the console's words
// for one, the tables' mark and its legend, and the run's last line. A
// noisy job's median, and so its place in a ranking, is not pinned down by
// its frames.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// The mark the tables put in a noisy job's row.
inline constexpr const char* kNoisyMark = "†";

// Whether `r` finished ok and its record judged its times noisy.
bool is_noisy(const record::JobRecord& r);

// "noisy ±7.2 %": the wider of its frame time's and frame ratio's intervals,
// for a noisy job; nullopt for another.
std::optional<std::string> noisy_label(const record::JobRecord& r);

// The least and the greatest threshold the noisy ones among `records` were
// judged by (records keep theirs); nullopt when none is noisy.
std::optional<std::pair<double, double>> noisy_thresholds(
    const std::vector<const record::JobRecord*>& records);

// "noisy: the median's 95 % interval (frame time or frame/control ratio) is
// wider than ±5 % (frames.noise_threshold); its rank may not hold", the
// thresholds of the noisy ones among `records`; "" when none is noisy. The
// tables print it after the mark.
std::string noisy_legend(const std::vector<const record::JobRecord*>& records);

// The run's last line: "warning: 2 of 12 timed jobs were noisy (the median's
// 95 % interval wider than ±5 %); the load average was 1.9–3.4 on 2 cores";
// nullopt when none was noisy.
std::optional<std::string> noise_warning(const std::vector<record::JobRecord>& records);

}  // namespace sb::results
