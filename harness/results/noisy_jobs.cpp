#include "results/noisy_jobs.h"

#include <algorithm>

#include "core/format_number.h"

namespace sb::results {

using core::format_number;
using record::JobRecord;
using record::JobStatus;
using record::NoiseRecord;

namespace {

const NoiseRecord* noise_of(const JobRecord& r) {
  if (r.status != JobStatus::Ok || !r.timing || !r.timing->noise) return nullptr;
  return &*r.timing->noise;
}

// "±5 %", or "±2–5 %" for records judged by several thresholds; "" when
// none of them is noisy.
std::string thresholds(const std::vector<const JobRecord*>& records) {
  const auto range = noisy_thresholds(records);
  if (!range) return "";
  std::string out = "±" + format_number("%g", 100.0 * range->first);
  if (range->second != range->first) out += "–" + format_number("%g", 100.0 * range->second);
  return out + " %";
}

}  // namespace

bool is_noisy(const JobRecord& r) {
  const NoiseRecord* n = noise_of(r);
  return n != nullptr && n->noisy;
}

std::optional<std::pair<double, double>> noisy_thresholds(
    const std::vector<const JobRecord*>& records) {
  std::optional<std::pair<double, double>> out;
  for (const JobRecord* r : records) {
    if (!is_noisy(*r)) continue;
    const double t = r->timing->noise->threshold;
    out = out ? std::pair(std::min(out->first, t), std::max(out->second, t)) : std::pair(t, t);
  }
  return out;
}

std::optional<std::string> noisy_label(const JobRecord& r) {
  if (!is_noisy(r)) return std::nullopt;
  return "noisy ±" + format_number("%.1f", 100.0 * r.timing->noise->judged_ci_rel()) + " %";
}

std::string noisy_legend(const std::vector<const JobRecord*>& records) {
  const std::string over = thresholds(records);
  if (over.empty()) return "";
  return "noisy: the median's 95 % interval (frame time or frame/control ratio) is wider than " +
         over + " (frames.noise_threshold); its rank may not hold";
}

std::optional<std::string> noise_warning(const std::vector<JobRecord>& records) {
  std::vector<const JobRecord*> timed;
  for (const JobRecord& r : records)
    if (noise_of(r) != nullptr) timed.push_back(&r);
  const auto noisy =
      std::count_if(timed.begin(), timed.end(), [](const JobRecord* r) { return is_noisy(*r); });
  if (noisy == 0) return std::nullopt;
  std::string out = "warning: " + std::to_string(noisy) + " of " + std::to_string(timed.size()) +
                    " timed jobs were noisy (the median's 95 % interval wider than " +
                    thresholds(timed) + ")";
  // The load the run saw, over every timed job's start and end.
  std::optional<double> least, most;
  std::int64_t cores = 0;
  for (const JobRecord* r : timed) {
    const NoiseRecord& n = *r->timing->noise;
    for (const auto& load : {n.load_average_start, n.load_average_end}) {
      if (!load) continue;
      least = std::min(least.value_or(*load), *load);
      most = std::max(most.value_or(*load), *load);
    }
    cores = std::max(cores, n.usable_cores);
  }
  if (least)
    out += "; the load average was " + format_number("%.1f", *least) + "–" +
           format_number("%.1f", *most) + " on " + std::to_string(cores) + " core" +
           (cores == 1 ? "" : "s");
  return out;
}

}  // namespace sb::results
