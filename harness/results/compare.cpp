#include "results/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "core/error.h"
#include "core/format_number.h"
#include "record/figures.h"
#include "record/timing_stats.h"
#include "results/mann_whitney.h"
#include "results/multiple_testing.h"
#include "results/reference_identity.h"

namespace sb::results {

using core::format_number;
using core::InputError;
using record::field_differences;
using record::host_fingerprint_fields;
using record::JobRecord;
using record::MetricPath;
using record::summarize;

namespace {

// timing.<key>.samples_ms: "frame" or "technique"; the finite ones.
std::vector<double> time_samples(const JobRecord& record, const std::string& key) {
  std::vector<double> out;
  if (!record.timing) return out;
  const record::Series& series =
      key == "technique" ? record.timing->technique : record.timing->frame;
  for (const double d : series.samples)
    if (std::isfinite(d)) out.push_back(d);
  return out;
}

// The per-frame ratios to the control: timing.control.frame_ratio.samples
// for "frame"; technique frame i / control frame i for "technique". The
// finite ones; nullopt without timing.control.
std::optional<std::vector<double>> ratio_samples(const JobRecord& record, const std::string& key) {
  if (!record.timing || !record.timing->control) return std::nullopt;
  const record::ControlTiming& control = *record.timing->control;
  std::vector<double> out;
  if (key == "technique") {
    const auto& job = record.timing->technique.samples;
    const auto& ctl = control.frame.samples;
    for (size_t i = 0; i < job.size() && i < ctl.size(); ++i)
      if (ctl[i] > 0 && std::isfinite(job[i] / ctl[i])) out.push_back(job[i] / ctl[i]);
  } else {
    for (const double d : control.frame_ratio.samples)
      if (std::isfinite(d)) out.push_back(d);
  }
  return out;
}

// What "--timing X" compares, for the table and the notes.
std::string time_label(const CompareOptions& o) {
  return o.normalize == "control" ? o.timing + "/control ratio" : o.timing + " time";
}

// The pair of fingerprints of one job in `pairs`, added when new.
FingerprintPair& pair_of(std::vector<FingerprintPair>& pairs,
                         const std::optional<std::string>& base,
                         const std::optional<std::string>& fresh) {
  for (auto& p : pairs)
    if (p.base == base.value_or("") && p.fresh == fresh.value_or("")) return p;
  FingerprintPair p;
  p.base = base.value_or("");
  p.fresh = fresh.value_or("");
  pairs.push_back(std::move(p));
  return pairs.back();
}

// Notes the hosts and builds of a job's two records in `out`; returns the
// host pair.
const FingerprintPair& note_fingerprints(const JobRecord& rb, const JobRecord& rn,
                                         CompareResult& out) {
  FingerprintPair& host = pair_of(out.hosts, rb.host.fingerprint, rn.host.fingerprint);
  if (host.jobs++ == 0 && !host.same()) {
    if (host.base.empty()) host.differences.push_back("BASE's records have no host fingerprint");
    if (host.fresh.empty()) host.differences.push_back("NEW's records have no host fingerprint");
    if (!host.base.empty() && !host.fresh.empty())
      host.differences =
          field_differences(host_fingerprint_fields(rb.host, rb.gl_renderer, rb.gl_version),
                            host_fingerprint_fields(rn.host, rn.gl_renderer, rn.gl_version));
  }
  FingerprintPair& build = pair_of(out.builds, rb.build.fingerprint, rn.build.fingerprint);
  if (build.jobs++ == 0 && !build.same())
    build.differences = field_differences(record::build_fingerprint_fields(rb.build),
                                          record::build_fingerprint_fields(rn.build));
  return host;
}

// Notes in `out` a technique whose plugin differs between a job's two
// records (records without a plugin identity say nothing).
void note_plugin(const JobRecord& rb, const JobRecord& rn, CompareResult& out) {
  const auto& pb = rb.technique.plugin;
  const auto& pn = rn.technique.plugin;
  if (!pb || !pn || pb->sha256 == pn->sha256) return;
  const std::string& name = rn.technique.name;
  for (const auto& d : out.plugins)
    if (d.technique == name) return;
  out.plugins.push_back({name, *pb, *pn});
}

// The names of the differing fields ("cpu.model, gl_renderer"), for a job's note.
std::string differing_fields(const FingerprintPair& host) {
  std::string names;
  for (const auto& d : host.differences)
    names += (names.empty() ? "" : ", ") + d.substr(0, d.find(':'));
  return names;
}

// "visibility.all.rmse" of a metric option, also spelt "metrics.visibility.all.rmse".
std::optional<MetricPath> metric_path(const std::string& option) {
  return MetricPath::parse(option.rfind("metrics.", 0) == 0 ? option.substr(8) : option);
}

// Metrics where a larger value is better (record/figures.h): an increase is
// an improvement.
bool higher_is_better(const std::string& path) {
  const std::optional<MetricPath> p = metric_path(path);
  return p && p->higher_is_better();
}

std::string metric_label(const std::string& path) {
  return path.substr(path.find_last_of('.') + 1);
}

std::string error_text(const std::optional<double>& v) {
  if (!v) return "-";
  if (std::isnan(*v)) return "nan";
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  return format_number("%.5f", *v);
}

}  // namespace

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::kUnchanged:
      return "unchanged";
    case Verdict::kRegression:
      return "REGRESSION";
    case Verdict::kImprovement:
      return "improvement";
    case Verdict::kNotCompared:
      break;
  }
  return "-";
}

bool JobComparison::regressed() const {
  return time == Verdict::kRegression || error == Verdict::kRegression ||
         (base_status == "ok" && new_status == "failed");
}

std::optional<double> metric_value(const JobRecord& record, const std::string& dotted_path) {
  const auto path = metric_path(dotted_path);
  return path ? record.metric(*path) : std::nullopt;
}

// "BASE", "NEW", "BASE and NEW" or "": which records lack the metric's region.
std::string side_without_region(const JobRecord& rb, const JobRecord& rn,
                                const std::string& metric) {
  const auto path = metric_path(metric);
  if (!path || !rb.metrics || !rn.metrics) return "";
  const bool base = path->holds(*rb.metrics), fresh = path->holds(*rn.metrics);
  return base && fresh ? "" : !base && !fresh ? "BASE and NEW" : !base ? "BASE" : "NEW";
}

void check_options(const CompareOptions& o) {
  if (!(o.alpha > 0 && o.alpha < 1))
    throw InputError("", "--alpha",
                     "expected a value in (0, 1), found " + format_number("%g", o.alpha));
  if (!(o.time_threshold >= 0) || !std::isfinite(o.time_threshold))
    throw InputError("", "--time-threshold",
                     "expected a relative change >= 0 (0.10 is 10 %), found " +
                         format_number("%g", o.time_threshold));
  if (!(o.error_threshold >= 0) || !std::isfinite(o.error_threshold))
    throw InputError(
        "", "--error-threshold",
        "expected an absolute change >= 0, found " + format_number("%g", o.error_threshold));
  if (o.timing != "frame" && o.timing != "technique" && o.timing != "none")
    throw InputError("", "--timing", "expected frame, technique or none, found '" + o.timing + "'");
  if (o.normalize != "none" && o.normalize != "control")
    throw InputError("", "--normalize", "expected none or control, found '" + o.normalize + "'");
  if (!parse_correction(o.correction))
    throw InputError("", "--correction", "expected holm, bh or none, found '" + o.correction + "'");
  if (o.metric != "none" && !metric_path(o.metric))
    throw InputError("", "--metric",
                     "no record has metrics." + o.metric + ": expected " +
                         record::metric_path_syntax() +
                         " (try visibility.all.rmse, visibility.penumbra.rmse, shaded.all.ssim)");
}

namespace {

// The lines about hosts and builds under the table's header: whether the
// timings are from one host, and if not what differs and what was done.
std::string format_hosts(const CompareResult& r, const CompareOptions& o) {
  std::string s;
  const bool all_same = std::all_of(r.hosts.begin(), r.hosts.end(),
                                    [](const FingerprintPair& p) { return p.same(); });
  if (!r.hosts.empty() && all_same) {
    s += "host: same host fingerprint";
    if (r.hosts.size() == 1) s += " (" + r.hosts[0].base + ")";
    s += "\n";
  }
  for (const auto& p : r.hosts) {
    if (p.same()) continue;
    s += "host: the fingerprints differ (BASE " + (p.base.empty() ? "none" : p.base) + ", NEW " +
         (p.fresh.empty() ? "none" : p.fresh) + ", " + std::to_string(p.jobs) + " job(s)):\n";
    for (const auto& d : p.differences) s += "  " + d + "\n";
  }
  if (!all_same) {
    if (o.timing == "none")
      s += "  times are not compared (--timing none); error metrics are, whatever the host.\n";
    else if (o.normalize == "control")
      s += "  times are compared as ratios to the control job, measured on each host "
           "(--normalize control); error metrics are compared whatever the host.\n";
    else
      s += "  absolute times from different (or unknown) hosts do not compare: those jobs' time is "
           "not "
           "compared, and compare exits 2 unless something regressed (4).\n"
           "  error metrics are compared whatever the host. To compare times, use "
           "--normalize control (ratios to the control job); for errors only, --timing none.\n";
  }
  for (const auto& p : r.builds) {
    if (p.same() || p.differences.empty()) continue;
    s += "build: differs (shown, not refused):\n";
    for (const auto& d : p.differences) s += "  " + d + "\n";
  }
  return s;
}

// A SHA-256 as its first digits, enough to tell two apart.
std::string short_hash(const std::string& hex) {
  constexpr size_t kShown = 12;
  return hex.size() > kShown ? hex.substr(0, kShown) + ".." : hex;
}

// A line per technique whose plugin differs: information, not a refusal.
std::string format_plugins(const CompareResult& r) {
  std::string s;
  for (const auto& d : r.plugins) {
    s += "plugin " + d.fresh.file + " differs: sha256 " + short_hash(d.base.sha256) + " vs " +
         short_hash(d.fresh.sha256);
    if (d.base.file != d.fresh.file) s += " (BASE's file " + d.base.file + ")";
    s += " (technique " + d.technique + "; shown, not refused)\n";
  }
  return s;
}

// The lines about the references under the table's header: which jobs'
// references differ, in what, and whether their errors were compared.
std::string format_references(const CompareResult& r, const CompareOptions& o) {
  std::string s;
  for (const auto& d : r.references) {
    s += "reference: differs for " + std::to_string(d.jobs.size()) + " job(s)";
    if (o.allow_reference_change)
      s += "; errors compared anyway (--allow-reference-change): a change of error may be the "
           "reference's, not the technique's:\n";
    else
      s += "; their errors are not compared (a change of error could be the reference's), and "
           "compare exits 2 unless something regressed (4). --allow-reference-change compares "
           "them anyway; --metric none compares times only:\n";
    for (const auto& line : d.differences) s += "  " + line + "\n";
    std::string jobs;
    for (const auto& id : d.jobs) jobs += (jobs.empty() ? "" : ", ") + id;
    s += "  jobs: " + jobs + "\n";
  }
  if (r.references_without_key > 0)
    s += "reference: " + std::to_string(r.references_without_key) +
         " job(s) have no reference cache_key on either side (records from before it was "
         "always written): checked on method, spp, seed, embree_isa and adaptive settings only\n";
  return s;
}

// The time verdict of one job that is ok on both sides.
void compare_time(const JobRecord& rb, const JobRecord& rn, const FingerprintPair& host,
                  const CompareOptions& o, JobComparison& c) {
  if (o.timing == "none") return;
  // Brackets of different rules charge different work (a GPU's timestamps
  // count a technique's CPU work, its old elapsed-time queries did not), so
  // neither their times nor their ratios compare. Older records name none.
  if (!rb.timing_source.empty() && !rn.timing_source.empty() &&
      rb.timing_source != rn.timing_source) {
    c.time_refused = true;
    c.note = "time not compared: the timing brackets differ (BASE " + rb.timing_source + ", NEW " +
             rn.timing_source + "; docs/results.md, timing_source)";
    return;
  }
  std::vector<double> sbase, sn;
  if (o.normalize == "control") {
    const auto rbase = ratio_samples(rb, o.timing), rnew = ratio_samples(rn, o.timing);
    if (!rbase || !rnew) {
      c.time_refused = true;
      c.note = "time not compared: no timing.control in " +
               std::string(!rbase && !rnew ? "BASE and NEW"
                           : !rbase        ? "BASE"
                                           : "NEW") +
               " (run with a control job: frames.control, docs/config.md)";
      return;
    }
    if (rb.timing->control->technique != rn.timing->control->technique)
      throw InputError("", "--normalize control",
                       c.job_id + ": BASE's control is " + rb.timing->control->technique +
                           ", NEW's is " + rn.timing->control->technique +
                           ": ratios to different controls do not compare");
    // A job that is its own control has the ratio 1 whatever happens to it:
    // judging it would only add a test that cannot fail to the family.
    if (rn.technique_variant == rn.timing->control->technique) {
      c.note = "time not judged: this job is the control (its ratio is 1 by construction)";
      return;
    }
    sbase = *rbase;
    sn = *rnew;
  } else {
    if (!host.same()) {
      c.time_refused = true;
      c.note = "time not compared: the hosts differ (" + differing_fields(host) + "; see above)";
      return;
    }
    sbase = time_samples(rb, o.timing);
    sn = time_samples(rn, o.timing);
  }
  c.base_samples = sbase.size();
  c.new_samples = sn.size();
  if (sbase.empty() || sn.empty()) {
    c.note = "no " + o.timing + " samples (" +
             (o.normalize == "control" ? std::string("timing.control")
                                       : "timing." + o.timing + ".samples_ms") +
             ") in " + std::string(sbase.empty() ? "BASE" : "NEW");
    return;
  }
  c.base_median_ms = summarize(sbase).median;
  c.new_median_ms = summarize(sn).median;
  c.change = c.base_median_ms > 0 ? c.new_median_ms / c.base_median_ms - 1 : 0;
  c.p = mann_whitney_u(sbase, sn).p;  // judged in judge_times, across the jobs
}

// The time verdicts, once every job's p is known: each p adjusted across
// the jobs tested, then compared with alpha.
void judge_times(CompareResult& out, const CompareOptions& o) {
  std::vector<JobComparison*> tested;
  std::vector<double> p;
  for (auto& c : out.jobs)
    if (c.p) {
      tested.push_back(&c);
      p.push_back(*c.p);
    }
  out.time_tests = int(tested.size());
  const std::vector<double> adjusted = adjust_p_values(p, *parse_correction(o.correction));
  for (size_t i = 0; i < tested.size(); ++i) {
    JobComparison& c = *tested[i];
    c.p_adjusted = adjusted[i];
    const bool significant = adjusted[i] < o.alpha;
    c.time = significant && c.change > o.time_threshold    ? Verdict::kRegression
             : significant && c.change < -o.time_threshold ? Verdict::kImprovement
                                                           : Verdict::kUnchanged;
  }
}

void add_note(JobComparison& c, const std::string& note) {
  c.note += (c.note.empty() ? "" : "; ") + note;
}

// Whether the job's errors compare: the same reference on both sides
// (results/reference_identity.h). Notes a difference in `out` and the job.
bool same_reference(const JobRecord& rb, const JobRecord& rn, const CompareOptions& o,
                    JobComparison& c, CompareResult& out) {
  const auto fb = reference_identity_fields(rb.reference);
  const auto fn = reference_identity_fields(rn.reference);
  if (fb.back().second.empty() && fn.back().second.empty()) ++out.references_without_key;
  const std::vector<std::string> differences = field_differences(fb, fn);
  if (differences.empty()) return true;
  auto group =
      std::find_if(out.references.begin(), out.references.end(),
                   [&](const ReferenceDifference& d) { return d.differences == differences; });
  if (group == out.references.end()) {
    out.references.push_back({differences, {}});
    group = out.references.end() - 1;
  }
  group->jobs.push_back(c.job_id);
  std::string names;
  for (const auto& d : differences) names += (names.empty() ? "" : ", ") + d.substr(0, d.find(':'));
  if (o.allow_reference_change) {
    add_note(c, "the references differ (" + names +
                    "); error compared anyway (--allow-reference-change)");
    return true;
  }
  add_note(c, "error not compared: the references differ (" + names + "; see above)");
  return false;
}

}  // namespace

CompareResult compare_runs(const std::vector<JobRecord>& base, const std::vector<JobRecord>& fresh,
                           const CompareOptions& o) {
  check_options(o);
  auto index = [](const std::vector<JobRecord>& records, std::vector<std::string>& order) {
    std::map<std::string, const JobRecord*> m;
    for (const auto& r : records)
      if (m.emplace(r.job_id, &r).second) order.push_back(r.job_id);
    return m;
  };
  std::vector<std::string> base_order, new_order;
  const auto b = index(base, base_order);
  const auto n = index(fresh, new_order);

  CompareResult out;
  bool metric_seen = false;
  for (const auto& id : base_order) {
    const auto it = n.find(id);
    if (it == n.end()) {
      out.only_base.push_back(id);
      continue;
    }
    const JobRecord& rb = *b.at(id);
    const JobRecord& rn = *it->second;
    JobComparison c;
    c.job_id = id;
    c.base_status = to_string(rb.status);
    c.new_status = to_string(rn.status);
    note_plugin(rb, rn, out);
    if (c.base_status != "ok" || c.new_status != "ok") {
      if (c.base_status == "ok" && c.new_status == "failed")
        c.note = "failed in NEW: " + rn.reason.value_or("");
      else
        c.note = "status " + c.base_status + " -> " + c.new_status;
      out.jobs.push_back(std::move(c));
      continue;
    }

    // Time.
    const FingerprintPair& host = note_fingerprints(rb, rn, out);
    compare_time(rb, rn, host, o, c);

    // Error.
    if (o.metric == "none") {
      out.jobs.push_back(std::move(c));
      continue;
    }
    c.base_error = metric_value(rb, o.metric);
    c.new_error = metric_value(rn, o.metric);
    metric_seen = metric_seen || c.base_error || c.new_error;
    // A region one side never measured (a baseline from before it existed)
    // reads NaN; compared, NaN -> number would pass as an improvement.
    const std::string missing =
        c.base_error && c.new_error ? side_without_region(rb, rn, o.metric) : std::string();
    if (!missing.empty()) {
      c.error_refused = true;
      add_note(c, "error not compared: " + missing + "'s record has no " + o.metric +
                      " (measured before that region existed?): re-record it, or pick "
                      "another --metric");
    } else if (c.base_error && c.new_error && !same_reference(rb, rn, o, c, out)) {
      c.error_refused = true;
    } else if (c.base_error && c.new_error) {
      const double eb = *c.base_error, en = *c.new_error;
      if (std::isnan(eb) && std::isnan(en)) {
        c.error = Verdict::kUnchanged;
      } else if (std::isnan(en)) {
        c.error = Verdict::kRegression;  // lost a finite error
      } else if (std::isnan(eb)) {
        c.error = Verdict::kImprovement;
      } else {
        double worse = en - eb;
        if (higher_is_better(o.metric)) worse = -worse;
        if (std::isinf(eb) && std::isinf(en) && eb == en) worse = 0;
        c.error = worse > o.error_threshold    ? Verdict::kRegression
                  : worse < -o.error_threshold ? Verdict::kImprovement
                                               : Verdict::kUnchanged;
      }
    }
    out.jobs.push_back(std::move(c));
  }
  for (const auto& id : new_order)
    if (!b.count(id)) out.only_new.push_back(id);
  judge_times(out, o);

  bool any_ok = false;
  for (const auto& c : out.jobs) any_ok = any_ok || (c.base_status == "ok" && c.new_status == "ok");
  if (any_ok && !metric_seen && o.metric != "none")
    throw InputError("", "--metric",
                     "no record has metrics." + o.metric +
                         " (try visibility.all.rmse, visibility.penumbra.rmse, shaded.all.ssim)");
  for (const auto& c : out.jobs) {
    if (c.time_refused) ++out.time_refused;
    if (c.error_refused) ++out.error_refused;
    if (c.regressed())
      ++out.regressions;
    else if (c.time == Verdict::kImprovement || c.error == Verdict::kImprovement)
      ++out.improvements;
  }
  return out;
}

int compare_exit_code(const CompareResult& r) {
  if (r.regressions > 0) return kExitRegression;
  return r.time_refused > 0 || r.error_refused > 0 ? core::kExitBadInput : core::kExitOk;
}

namespace {

// How alpha applies: after the correction across the jobs tested, or per job.
std::string alpha_scope(const CompareResult& r, const CompareOptions& o) {
  const Correction c = *parse_correction(o.correction);
  if (c == Correction::kNone) return " per job (--correction none)";
  return std::string(" after ") + correction_name(c) + "'s correction across the " +
         std::to_string(r.time_tests) + " job(s) tested (--correction " + to_string(c) + ")";
}

}  // namespace

std::string format_comparison(const CompareResult& r, const CompareOptions& o) {
  size_t w = 3;
  for (const auto& c : r.jobs) w = std::max(w, c.job_id.size());
  const std::string label = metric_label(o.metric);
  const bool ratios = o.normalize == "control";
  std::string s;
  char line[1024];
  if (o.timing == "none")
    s += "time: not compared (--timing none); ";
  else
    s += "time: Mann-Whitney U on " + time_label(o) + "s" +
         (ratios ? " (--normalize control)" : ", absolute (--normalize none)") +
         format_number(", alpha %g", o.alpha) + alpha_scope(r, o) +
         format_number(", threshold %.1f %%; ", o.time_threshold * 100);
  if (o.metric == "none")
    s += "error: not compared (--metric none)\n";
  else
    s += "error: " + o.metric + format_number(", threshold %g (absolute)\n", o.error_threshold);
  s += format_hosts(r, o);
  s += format_plugins(r);
  s += format_references(r, o);
  s += "\n";
  const char* unit = ratios ? "ratio" : "ms";
  std::snprintf(line, sizeof line, "%-*s %10s %10s %8s %8s %8s  %-12s %10s %10s  %s\n", int(w),
                "job", (std::string("base ") + unit).c_str(), (std::string("new ") + unit).c_str(),
                "change", "p", "p adj", "time", (label + " base").c_str(), (label + " new").c_str(),
                "error");
  s += line;
  for (const auto& c : r.jobs) {
    const bool timed = c.time != Verdict::kNotCompared;
    const char* median = ratios ? "%.4f" : "%.3f";
    const auto p_text = [](const std::optional<double>& p) {
      return p ? format_number(*p < 1e-3 ? "%.1e" : "%.4f", *p) : std::string("-");
    };
    std::snprintf(
        line, sizeof line, "%-*s %10s %10s %8s %8s %8s  %-12s %10s %10s  %s\n", int(w),
        c.job_id.c_str(), timed ? format_number(median, c.base_median_ms).c_str() : "-",
        timed ? format_number(median, c.new_median_ms).c_str() : "-",
        timed ? format_number("%+.1f%%", std::fabs(c.change) < 5e-4 ? 0.0 : c.change * 100).c_str()
              : "-",
        p_text(c.p).c_str(), p_text(c.p_adjusted).c_str(),
        c.time_refused ? "not compared" : to_string(c.time), error_text(c.base_error).c_str(),
        error_text(c.new_error).c_str(), c.error_refused ? "not compared" : to_string(c.error));
    s += line;
  }
  bool notes = false;
  for (const auto& c : r.jobs) {
    if (c.note.empty() && !c.regressed()) continue;
    if (!notes) s += "\n";
    notes = true;
    s += "  " + c.job_id + ": " + (c.note.empty() ? "" : c.note);
    if (c.regressed()) {
      std::string what;
      if (c.time == Verdict::kRegression)
        what += time_label(o) + format_number(" %+.1f %%", c.change * 100) +
                format_number(" (p = %.2g", c.p.value_or(1)) +
                format_number(", adjusted %.2g)", c.p_adjusted.value_or(1));
      if (c.error == Verdict::kRegression)
        what += std::string(what.empty() ? "" : ", ") + label + " " + error_text(c.base_error) +
                " -> " + error_text(c.new_error);
      if (!what.empty()) s += (c.note.empty() ? "" : "; ") + std::string("regression: ") + what;
    }
    s += "\n";
  }
  if (!r.only_base.empty()) {
    s += "\nonly in BASE (" + std::to_string(r.only_base.size()) + "):\n";
    for (const auto& id : r.only_base) s += "  " + id + "\n";
  }
  if (!r.only_new.empty()) {
    s += "\nonly in NEW (" + std::to_string(r.only_new.size()) + "):\n";
    for (const auto& id : r.only_new) s += "  " + id + "\n";
  }
  std::snprintf(line, sizeof line, "\n%zu job(s) compared: %d regression(s), %d improvement(s)",
                r.jobs.size(), r.regressions, r.improvements);
  s += line;
  if (r.time_refused > 0) s += ", " + std::to_string(r.time_refused) + " with time not compared";
  if (r.error_refused > 0) s += ", " + std::to_string(r.error_refused) + " with error not compared";
  s += "\n";
  return s;
}

}  // namespace sb::results
