// The history's change-point detector on simulated histories: how often it
// reports a step that is not there (noise that carries from run to run, busy
// spells of a few runs) and how soon it finds one that is, before (one
// residual round, no serial correlation, no runs' own noise: the detector as
// it was) and after. Prints a Markdown table (docs/ci.md, "The history's
// detector").
//
//   build/bench/change_point_grid [--series 2000] [--seed 1]
//       [--steady-own 0.01] [--busy-own 0.06] [--busy-step 0.15]
//   build/bench/change_point_grid --db history.sqlite
//       the same three detectors on a real history's time ratios: every
//       series' steps, and each run's own noise against the series' median
//
// A history is 20 runs, value = level * exp(noise), noise as the condition
// says (marginal spread 5 %, or 3 % for the detection rows). Each run's own
// noise (the standard error of its median, as its record measured it) is
// steady-own times exp(0.3 z) for a steady run and busy-own for a run in a
// busy spell; "own noise" rows give it to the detector, the others do not
// (records without it).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "history/change_points.h"
#include "history/history_db.h"

namespace {

using sb::history::ChangePointOptions;
using sb::history::find_change_points;

struct Settings {
  int series = 2000;
  unsigned long seed = 1;
  double steady_own = 0.01, busy_own = 0.06, busy_step = 0.15;
  double beta = ChangePointOptions{}.beta;  // the detector's after
};

struct History {
  std::vector<double> values, own;
};

// AR(1) noise of marginal spread `sigma` and lag-1 correlation phi.
std::vector<double> ar1(std::mt19937_64& rng, size_t n, double sigma, double phi) {
  std::normal_distribution<double> z(0, 1);
  std::vector<double> e(n);
  e[0] = sigma * z(rng);
  for (size_t i = 1; i < n; ++i) e[i] = phi * e[i - 1] + sigma * std::sqrt(1 - phi * phi) * z(rng);
  return e;
}

std::vector<double> steady_own(std::mt19937_64& rng, size_t n, double typical) {
  std::normal_distribution<double> z(0, 1);
  std::vector<double> own(n);
  for (double& o : own) o = typical * std::exp(0.3 * z(rng));
  return own;
}

// n runs, phi-correlated noise, a busy spell of `spell` runs (+busy_step,
// own noise busy_own) at a random place, a step of `step` from run `at`.
History make(std::mt19937_64& rng, const Settings& s, size_t n, double sigma, double phi,
             size_t spell, double step, size_t at) {
  History h;
  const std::vector<double> e = ar1(rng, n, sigma, phi);
  h.own = steady_own(rng, n, s.steady_own);
  size_t from = n;
  if (spell > 0) from = std::uniform_int_distribution<size_t>(0, n - spell)(rng);
  for (size_t i = 0; i < n; ++i) {
    double level = i >= at ? 1 + step : 1.0;
    if (i >= from && i < from + spell) {
      level *= 1 + s.busy_step;
      h.own[i] = s.busy_own;
    }
    h.values.push_back(level * std::exp(e[i]));
  }
  return h;
}

// Share of histories for which `hit` holds, in %.
double share(const Settings& s, unsigned long salt,
             const std::function<bool(std::mt19937_64&)>& hit) {
  std::mt19937_64 rng(s.seed * 1000003 + salt);
  int hits = 0;
  for (int i = 0; i < s.series; ++i) hits += hit(rng) ? 1 : 0;
  return 100.0 * hits / s.series;
}

enum class Detector { kBefore, kAfterValuesOnly, kAfterWithOwnNoise };

ChangePointOptions options_of(Detector d, const Settings& s) {
  ChangePointOptions o;
  if (d == Detector::kBefore) {
    o.serial_correlation = false;
    o.beta = 7;
  } else {
    o.beta = s.beta;
  }
  return o;
}

bool any_step(const History& h, Detector d, const Settings& s) {
  const ChangePointOptions o = options_of(d, s);
  const std::vector<double> none;
  return !find_change_points(h.values, d == Detector::kAfterWithOwnNoise ? h.own : none, o).empty();
}

// A step up reported at run `at`, or up to `slack` runs from it.
bool step_found_at(const History& h, Detector d, const Settings& s, size_t at, size_t slack) {
  const ChangePointOptions o = options_of(d, s);
  const std::vector<double> none;
  for (const auto& c :
       find_change_points(h.values, d == Detector::kAfterWithOwnNoise ? h.own : none, o))
    if (c.index + slack >= at && c.index <= at + slack && c.relative_change > 0) return true;
  return false;
}

void row(const char* what, const std::function<double(Detector)>& rate) {
  std::printf("| %s | %.1f %% | %.1f %% | %.1f %% |\n", what, rate(Detector::kBefore),
              rate(Detector::kAfterValuesOnly), rate(Detector::kAfterWithOwnNoise));
}

double parse(const char* flag, const char* value) {
  char* end = nullptr;
  const double v = std::strtod(value, &end);
  if (end == value || *end != '\0') {
    std::fprintf(stderr, "%s: not a number: %s\n", flag, value);
    std::exit(2);
  }
  return v;
}

// Every series of a real history: its time ratios, each run's own noise
// over the series' median own noise, and the steps each detector reports.
int report_history(const std::string& file) {
  const sb::history::HistoryDb db(file);
  for (const sb::history::QuantitySeries& q : db.series("time.frame_ratio")) {
    std::printf("%s\n  ratio:", q.series.c_str());
    for (double v : q.values) std::printf(" %.3f", v);
    std::printf("\n  own noise (%%):");
    for (double v : q.noise) std::printf(" %.1f", 100 * v);
    std::printf("\n");
    for (Detector d :
         {Detector::kBefore, Detector::kAfterValuesOnly, Detector::kAfterWithOwnNoise}) {
      ChangePointOptions o;
      o.serial_correlation = d != Detector::kBefore;
      const std::vector<double> none;
      const auto steps =
          find_change_points(q.values, d == Detector::kAfterWithOwnNoise ? q.noise : none, o);
      std::printf("  %s:", d == Detector::kBefore            ? "before"
                           : d == Detector::kAfterValuesOnly ? "after, values only"
                                                             : "after, own noise");
      if (steps.empty()) std::printf(" no step");
      for (const auto& c : steps)
        std::printf(" run %zu %+.1f %%", c.index + 1, 100 * c.relative_change);
      std::printf("\n");
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && !std::strcmp(argv[1], "--db")) return report_history(argv[2]);
  Settings s;
  for (int i = 1; i + 1 < argc; i += 2) {
    const double v = parse(argv[i], argv[i + 1]);
    if (!std::strcmp(argv[i], "--series"))
      s.series = static_cast<int>(v);
    else if (!std::strcmp(argv[i], "--seed"))
      s.seed = static_cast<unsigned long>(v);
    else if (!std::strcmp(argv[i], "--steady-own"))
      s.steady_own = v;
    else if (!std::strcmp(argv[i], "--busy-own"))
      s.busy_own = v;
    else if (!std::strcmp(argv[i], "--busy-step"))
      s.busy_step = v;
    else if (!std::strcmp(argv[i], "--beta"))
      s.beta = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  constexpr size_t kRuns = 20;
  std::printf(
      "%d histories of %zu runs per row; runs' own noise %.3g (steady), %.3g (busy); "
      "busy spells +%.0f %%\n\n",
      s.series, kRuns, s.steady_own, s.busy_own, 100 * s.busy_step);
  std::printf(
      "| histories without a step: any step reported | before | after, values only | "
      "after, with runs' own noise |\n|---|---|---|---|\n");
  unsigned long salt = 0;
  for (double phi : {0.0, 0.3, 0.5, 0.7}) {
    const std::string what =
        phi == 0 ? std::string("5 % noise, independent runs")
                 : "5 % noise, serial correlation " + std::to_string(phi).substr(0, 3);
    ++salt;
    row(what.c_str(), [&](Detector d) {
      return share(s, salt, [&](std::mt19937_64& rng) {
        return any_step(make(rng, s, kRuns, 0.05, phi, 0, 0, kRuns), d, s);
      });
    });
  }
  for (size_t spell : {2, 3}) {
    const std::string what = "5 % noise, a busy spell of " + std::to_string(spell) + " runs";
    ++salt;
    row(what.c_str(), [&](Detector d) {
      return share(s, salt, [&](std::mt19937_64& rng) {
        return any_step(make(rng, s, kRuns, 0.05, 0, spell, 0, kRuns), d, s);
      });
    });
  }
  std::printf(
      "\n| a +10 %% step after 15 runs | before | after, values only | "
      "after, with runs' own noise |\n|---|---|---|---|\n");
  for (double noise : {0.03, 0.05, 0.08})
    for (size_t after : {3, 5, 10})
      for (size_t slack : {0, 1}) {
        const size_t at = 15;
        const std::string what = std::to_string(std::lround(noise * 100)) + " % noise, " +
                                 std::to_string(after) + " runs after it: found " +
                                 (slack == 0 ? "at its run" : "within a run of it");
        ++salt;
        row(what.c_str(), [&](Detector d) {
          return share(s, salt, [&](std::mt19937_64& rng) {
            return step_found_at(make(rng, s, at + after, noise, 0, 0, 0.10, at), d, s, at, slack);
          });
        });
      }
  return 0;
}
