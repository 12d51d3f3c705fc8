#include "config/config_blocks.h"

#include <stdexcept>

#include "config/identity.h"
#include "config/param_table.h"
#include "reference/adaptive.h"
#include "reference/embree_isa.h"
#include "reference/settings.h"

namespace sb::config {

using core::bool_param;
using core::choice_param;
using core::Decides;
using core::float_param;
using core::int_param;
using core::ParamSpec;
using core::read_param_value;
using core::string_param;
using core::to_string;

namespace {

using json = nlohmann::json;

ConfigBlock frames_block() {
  ConfigBlock b{"frames", "frame counts", {}, nullptr, nullptr, nullptr};
  b.keys = {
      {Decides::Both,
       int_param("warmup", 2, 0, 100000,
                 "frames rendered and thrown away before the timed ones; one more untimed frame "
                 "always comes first, so shader compilation never lands in a timed frame, even "
                 "with 0"),
       [](Experiment& e, const json& v) { e.warmup_frames = v.get<int>(); },
       [](const Experiment& e) { return json(e.warmup_frames); }},
      {Decides::Both,
       int_param("timed", 10, 1, 100000,
                 "frames timed per job, or `\"auto\"`: blocks of `auto_block` frames until the "
                 "median's 95 % interval (frame time and frame ratio, as `noise_threshold` "
                 "judges them) is within ± `auto_target`, or a bound is reached; the record "
                 "says how many and why they stopped (`timing.auto`)"),
       nullptr,  // read by the block's finish: an integer or "auto"
       [](const Experiment& e) { return e.timed_auto ? json("auto") : json(e.timed_frames); },
       "integer or string", "1 … 100000, or `\"auto\"`"},
      {Decides::Timing,
       string_param("control", kDefaultControl,
                    "a technique entry (a name, or `{\"name\", \"params\"}` without a sweep) "
                    "whose frames are timed next to every job's, in ABBA order, so that each "
                    "record also holds its time as a ratio to the control's (`timing.control`); "
                    "`null` turns it off and halves the frames rendered"),
       nullptr,
       [](const Experiment& e) { return e.control ? json(e.control->name) : json(nullptr); },
       "technique or null"},
  };
  // The control's parameters and plugin decide its times as much as its name.
  b.keys.back().identity = [](const Experiment& e) {
    return e.control ? technique_identity(e, *e.control) : json(nullptr);
  };
  // A judgement of the times, not a number of them: a rerun with another
  // threshold keeps the records, which say the threshold they were judged by.
  b.keys.emplace_back(
      Decides::None,
      float_param("noise_threshold", 0.05, 0.0, 1.0,
                  "a job is noisy when its median frame time's 95 % interval (or its frame "
                  "ratio's) is wider than ± this fraction of the median (docs/results.md, "
                  "\"Noise\"); it is marked in the record (`timing.noise`), the console, "
                  "every table, and counted in the run's last line"),
      [](Experiment& e, const json& v) { e.noise_threshold = v.get<double>(); },
      [](const Experiment& e) { return json(e.noise_threshold); });
  b.keys.emplace_back(
      Decides::Timing,
      int_param("auto_block", 10, 1, 100000,
                "with `timed` \"auto\": the frames timed before the first look at the interval, "
                "and between two looks"),
      [](Experiment& e, const json& v) { e.timed_frames = v.get<int>(); },
      [](const Experiment& e) { return json(e.timed_frames); });
  // It sets the count `timed` holds, whose part of the identity it is.
  b.keys.back().identity = [](const Experiment&) { return json(nullptr); };
  b.keys.emplace_back(
      Decides::Timing,
      float_param("auto_target", 0.03, 0.001, 1.0,
                  "with `timed` \"auto\": the relative half-width of the median's 95 % interval "
                  "to reach"),
      [](Experiment& e, const json& v) { e.auto_target = v.get<double>(); },
      [](const Experiment& e) { return json(e.auto_target); });
  b.keys.emplace_back(
      Decides::Timing,
      int_param("auto_max_frames", 1000, 1, 1000000,
                "with `timed` \"auto\": at most this many timed frames per job"),
      [](Experiment& e, const json& v) { e.auto_max_frames = v.get<int>(); },
      [](const Experiment& e) { return json(e.auto_max_frames); });
  b.keys.emplace_back(
      Decides::Timing,
      float_param("auto_max_seconds", 10.0, 0.0, 86400.0,
                  "with `timed` \"auto\": no block starts after this many seconds of a job's "
                  "timed frames"),
      [](Experiment& e, const json& v) { e.auto_max_seconds = v.get<double>(); },
      [](const Experiment& e) { return json(e.auto_max_seconds); });
  b.keys.emplace_back(
      Decides::Error,
      int_param("history", 32, 1, 100000,
                "a temporal technique's frames depend on the frames before them (per-frame "
                "samples, temporal accumulation: `shadowbench list` marks it): its V is measured "
                "on this frame of a fresh `prepare()` on the still scene, so that its error does "
                "not depend on how many frames the timing took (`technique.measured_frame`); "
                "the other techniques' frames are all alike"),
      [](Experiment& e, const json& v) { e.history_frames = v.get<int>(); },
      [](const Experiment& e) { return json(e.history_frames); });
  // frames.timed: an integer, as the table says, or "auto"; auto_block and
  // timed cannot both give the count.
  b.finish = [](Experiment& e, const json& given, const ConfigReader& r) {
    if (!given.contains("timed")) return;
    const json& timed = given["timed"];
    if (timed.is_string() && timed.get<std::string>() == "auto") {
      e.timed_auto = true;
    } else if (timed.is_string()) {
      r.fail("/frames/timed", "expected an integer or \"auto\", found string " + timed.dump());
    } else {
      if (given.contains("auto_block"))
        r.fail("/frames/auto_block", "applies only with \"timed\": \"auto\"");
      for (const BlockKey& key : config_blocks().front().keys)
        if (key.spec.name == "timed")
          e.timed_frames = read_param_value(r, key.spec, timed, "/frames/timed", false).get<int>();
    }
    if (e.timed_auto && e.auto_max_frames < e.timed_frames)
      r.fail("/frames/auto_max_frames", "expected at least auto_block (" +
                                            std::to_string(e.timed_frames) + "), found " +
                                            std::to_string(e.auto_max_frames));
  };
  return b;
}

// true for "exact".
bool exact(const json& method) { return method.get<std::string>() == "exact"; }

void check_reference(Experiment& e, const json& ref, const ConfigReader& r) {
  const reference::Settings& s = e.reference.settings;
  if (e.reference.second_exact && *e.reference.second_exact == s.exact)
    r.fail("/reference/second_method",
           std::string("expected the other method than /reference/method (") +
               (s.exact ? "exact" : "monte_carlo") + "), found the same");
  if (s.adaptive) {
    // Whether the counts nest is the config's question, not the run's.
    const std::string why = reference::detail::adaptive_layout_problem(s.spp, s.pilot_spp);
    if (s.pilot_spp != 4 && s.pilot_spp != 16 && s.pilot_spp != 64)
      r.fail(ref.contains("pilot_spp") ? "/reference/pilot_spp" : "/reference/adaptive", why);
    if (!why.empty()) r.fail("/reference/spp", "with /reference/adaptive: " + why);
  }
  try {  // syntax only: whether this CPU has the ISA is the run's question
    reference::check_embree_config(s.embree_config);
  } catch (const std::invalid_argument& ex) {
    r.fail("/reference/embree_config", ex.what());
  }
}

ConfigBlock reference_block() {
  ConfigBlock b{"reference", "reference settings", {}, nullptr, check_reference, nullptr};
  const std::vector<std::string> methods{"monte_carlo", "exact"};
  ParamSpec second = choice_param(
      "second_method", "", methods,
      "also measures every job against a reference of the other method (record "
      "`second_reference`; docs/results.md, \"Two references\"); absent: one reference");
  second.default_value = nullptr;
  b.keys = {
      {Decides::Error,
       choice_param("method", "monte_carlo", methods,
                    "ray traced and stratified, or exact (docs/results.md, \"The exact "
                    "reference\": no samples, no noise; scenes it cannot do fall back to Monte "
                    "Carlo with the reason)"),
       [](Experiment& e, const json& v) { e.reference.settings.exact = exact(v); },
       [](const Experiment& e) {
         return json(e.reference.settings.exact ? "exact" : "monte_carlo");
       }},
      {Decides::Error, second,
       [](Experiment& e, const json& v) { e.reference.second_exact = exact(v); },
       [](const Experiment& e) {
         if (!e.reference.second_exact) return json(nullptr);
         return json(*e.reference.second_exact ? "exact" : "monte_carlo");
       }},
      {Decides::Error,
       int_param("spp", 256, 1, reference::kMaxSpp,
                 "samples per pixel of the Monte Carlo reference; with 1 the standard error is "
                 "unknown and reported as 0.5; adaptive: at most, and then `pilot_spp` × 4^K"),
       [](Experiment& e, const json& v) { e.reference.settings.spp = v.get<int>(); },
       [](const Experiment& e) { return json(e.reference.settings.spp); }},
      {Decides::Error, int_param("seed", 1, 0, 2147483647, "the Monte Carlo reference's seed"),
       [](Experiment& e, const json& v) { e.reference.settings.seed = v.get<uint64_t>(); },
       [](const Experiment& e) { return json(e.reference.settings.seed); }},
      {Decides::None,
       bool_param("cache", true, "keep references in the on-disk cache, either method"),
       [](Experiment& e, const json& v) { e.reference.cache = v.get<bool>(); },
       [](const Experiment& e) { return json(e.reference.cache); }},
      {Decides::Error,
       bool_param("adaptive", false,
                  "a `pilot_spp`-sample pilot per pixel, and more samples only where needed "
                  "(below, \"The adaptive reference\")"),
       [](Experiment& e, const json& v) { e.reference.settings.adaptive = v.get<bool>(); },
       [](const Experiment& e) { return json(e.reference.settings.adaptive); }},
      {Decides::Error,
       int_param("pilot_spp", 4, 1, reference::kMaxSpp,
                 "the adaptive reference's pilot: 4, 16 or 64"),
       [](Experiment& e, const json& v) { e.reference.settings.pilot_spp = v.get<int>(); },
       [](const Experiment& e) { return json(e.reference.settings.pilot_spp); }},
      {Decides::Error,
       float_param("target_std_error", 0.01, 1e-6, 0.5,
                   "the standard error the adaptive reference plans each pixel's level for"),
       [](Experiment& e, const json& v) {
         e.reference.settings.target_std_error = v.get<double>();
       },
       [](const Experiment& e) { return json(e.reference.settings.target_std_error); }},
      {Decides::Error,
       string_param("embree_config", "",
                    "Embree's ISA: `\"\"` (the environment's, or the best), `\"isa=avx2\"`, "
                    "`\"max_isa=avx2\"` (below)"),
       [](Experiment& e, const json& v) {
         e.reference.settings.embree_config = v.get<std::string>();
       },
       [](const Experiment& e) { return json(e.reference.settings.embree_config); }},
  };
  return b;
}

ConfigBlock stability_block() {
  ConfigBlock b{"stability", "stability settings", {}, nullptr, nullptr, nullptr};
  b.present = [](Experiment& e) { e.stability.emplace(); };
  b.in_effect = [](const Experiment& e) { return e.stability.has_value(); };
  ParamSpec frames = int_param("flicker_frames", 8, 0, 64,
                               "untimed frames per job under a moving light (0: none)");
  frames.rule = [](const json& v) {
    return v.get<int>() == 1 ? std::string("0 (off) or at least 2 frames") : std::string();
  };
  frames.rule_doc = "not 1";
  b.keys = {
      {Decides::Error, frames,
       [](Experiment& e, const json& v) { e.stability->flicker_frames = v.get<int>(); },
       [](const Experiment& e) { return json(e.stability->flicker_frames); }},
      {Decides::Error,
       float_param("flicker_step", 1.0 / 4096.0, 0, 0.1,
                   "the light's move per frame, × the casters' bounding-box diagonal (0 keeps it "
                   "still)"),
       [](Experiment& e, const json& v) { e.stability->flicker_step = v.get<double>(); },
       [](const Experiment& e) { return json(e.stability->flicker_step); }},
      {Decides::Error,
       float_param("flicker_factor", 2, 1, 1e6,
                   "degraded when the mean flicker is over this × the reference's own"),
       [](Experiment& e, const json& v) { e.stability->flicker_factor = v.get<double>(); },
       [](const Experiment& e) { return json(e.stability->flicker_factor); }},
      {Decides::Error,
       bool_param("sensitivity", true,
                  "a variant at p ± `sensitivity_step`·\\|p\\| for every continuous parameter "
                  "and for the light's size"),
       [](Experiment& e, const json& v) { e.stability->sensitivity = v.get<bool>(); },
       [](const Experiment& e) { return json(e.stability->sensitivity); }},
      {Decides::Error,
       float_param("sensitivity_step", 0.01, 1e-6, 0.5, "the relative step of `sensitivity`"),
       [](Experiment& e, const json& v) { e.stability->sensitivity_step = v.get<double>(); },
       [](const Experiment& e) { return json(e.stability->sensitivity_step); }},
      {Decides::Error,
       float_param("stiff_threshold", 0.5, 0, 1e6,
                   "degraded when a parameter's relative sensitivity is over it"),
       [](Experiment& e, const json& v) { e.stability->stiff_threshold = v.get<double>(); },
       [](const Experiment& e) { return json(e.stability->stiff_threshold); }},
      {Decides::Error,
       float_param("max_rmse", 0.1, 0, 1,
                   "degraded when the RMSE is over it (a scene entry may set its own)"),
       [](Experiment& e, const json& v) { e.stability->max_rmse = v.get<double>(); },
       [](const Experiment& e) { return json(e.stability->max_rmse); }},
  };
  return b;
}

ConfigBlock metrics_block() {
  ConfigBlock b{"metrics", "metric settings", {}, nullptr, nullptr, nullptr};
  b.keys = {
      {Decides::Error,
       bool_param("distance_thirds", false,
                  "also measure the visibility's error over the near, middle and far third of "
                  "the camera's distances (record regions `near_third`, `middle_third`, "
                  "`far_third`), for perspective aliasing; part of the jobs' spec"),
       [](Experiment& e, const json& v) { e.distance_thirds = v.get<bool>(); },
       [](const Experiment& e) { return json(e.distance_thirds); }},
      {Decides::Error,
       choice_param("distance_scale", "linear", {"linear", "log"},
                    "how `distance_thirds` divides the distances: equal intervals of distance, "
                    "or of its logarithm (equal ratios, as cascades split a view: a street seen "
                    "from eye height over a kilometre has nearly every pixel in the linear near "
                    "third); part of the jobs' spec"),
       [](Experiment& e, const json& v) {
         e.distance_scale = v.get<std::string>() == "log" ? metrics::DistanceScale::Log
                                                          : metrics::DistanceScale::Linear;
       },
       [](const Experiment& e) { return json(metrics::to_string(e.distance_scale)); }},
      {Decides::Error,
       float_param("flip_pixels_per_degree", metrics::kFlipDefaultPixelsPerDegree, 1, 1000,
                   "the viewing distance of the FLIP errors (`flip_mean`), in pixels per degree "
                   "of visual angle; the default is the paper's (a 0.7 m wide 3840-pixel monitor "
                   "seen from 0.7 m); part of the jobs' spec"),
       [](Experiment& e, const json& v) { e.flip_pixels_per_degree = v.get<double>(); },
       [](const Experiment& e) { return json(e.flip_pixels_per_degree); }},
  };
  return b;
}

ConfigBlock limits_block() {
  // Below a second a busy machine kills healthy jobs; a week is no limit.
  ConfigBlock b{"limits", "time limits", {}, nullptr, nullptr, nullptr};
  b.keys = {
      {Decides::None,
       float_param("job_seconds", 1800, 1, 604800,
                   "seconds one job (prepare, frames, metrics, images) may take; `run "
                   "--job-timeout` overrides it"),
       [](Experiment& e, const json& v) { e.limits.job_seconds = v.get<double>(); },
       [](const Experiment& e) { return json(e.limits.job_seconds); }},
      {Decides::None,
       float_param("setup_seconds", 3600, 1, 604800,
                   "seconds a (scene, resolution)'s set-up (scene, G-buffer, reference) may take"),
       [](Experiment& e, const json& v) { e.limits.setup_seconds = v.get<double>(); },
       [](const Experiment& e) { return json(e.limits.setup_seconds); }},
  };
  return b;
}

}  // namespace

const std::vector<ConfigBlock>& config_blocks() {
  static const std::vector<ConfigBlock> blocks{frames_block(), reference_block(), stability_block(),
                                               metrics_block(), limits_block()};
  return blocks;
}

void read_config_blocks(const ConfigReader& r, const json& doc, Experiment& e) {
  for (const ConfigBlock& b : config_blocks()) {
    if (!doc.contains(b.name)) continue;
    const json& given = r.object(doc[b.name], b.pointer(), b.what);
    std::vector<std::string> names;
    for (const BlockKey& k : b.keys) names.push_back(k.spec.name);
    r.only_keys(given, b.pointer(), names);
    if (b.present) b.present(e);
    for (const BlockKey& k : b.keys)
      if (k.store && given.contains(k.spec.name))
        // Integers must be written as integers: 2.0 is refused, unlike in a
        // technique parameter.
        k.store(e, read_param_value(r, k.spec, given[k.spec.name], b.pointer() + "/" + k.spec.name,
                                    false));
    if (b.finish) b.finish(e, given, r);
  }
}

std::string markdown_config_blocks() {
  std::string out;
  for (const ConfigBlock& b : config_blocks()) {
    out += "### `" + b.name + "`\n\n";
    out += "| key | type | default | accepted | decides | meaning |\n|---|---|---|---|---|---|\n";
    for (const BlockKey& k : b.keys) {
      const ParamSpec& s = k.spec;
      const bool technique = !k.type_doc.empty();
      out += "| `" + s.name + "` | " + (technique ? k.type_doc : to_string(s.type)) + " | `" +
             markdown_cell(s.default_value.is_null() ? "absent" : s.default_value.dump()) + "` | " +
             markdown_cell(!k.accepted_doc.empty() ? k.accepted_doc
                           : technique             ? "a technique entry"
                                                   : accepted_values(s, true)) +
             " | " + core::to_string(s.decides) + " | " + markdown_cell(s.doc) + " |\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace sb::config
