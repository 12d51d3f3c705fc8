#pragma once
// A run folder's plan.json as types: what plan/plan_json.h writes from a
// Plan and reads back (`merge` compares the shards' plans, and finds the
// planned jobs no folder recorded). Described once (record/describe.h), so
// its JSON, its reader and docs/results.md's table of it cannot drift.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// The version of plan.json's shape; a file of another is refused.
constexpr int kPlanVersion = 1;

// plan.json's "counts": jobs planned each way, over all shards.
struct PlanCounts {
  static constexpr RecordDoc kSchema{"PlanCounts", "jobs planned each way, over all shards"};

  std::int64_t run = 0, skip = 0, fail = 0;

  template <class V>
  static void describe(V& v) {
    v.field("run", &PlanCounts::run, {"", "jobs planned to run"});
    v.field("skip", &PlanCounts::skip, {"", "jobs planned to be skipped (a need the scene lacks)"});
    v.field("fail", &PlanCounts::fail,
            {"", "jobs planned to fail (their plugin did not load or their scene did not build)"});
  }
  bool operator==(const PlanCounts&) const = default;
};

// One scene variant of the plan.
struct PlannedSceneRecord {
  static constexpr RecordDoc kSchema{"PlannedSceneRecord",
                                     "one scene variant as planned, in config order"};

  std::string name;
  std::string error;  // why the scene did not build; "" when it did
  bool bad_input = false;
  std::string input_error;
  std::vector<std::string> log;

  template <class V>
  static void describe(V& v) {
    v.field("name", &PlannedSceneRecord::name, {"", "the scene variant's name"});
    v.field("error", &PlannedSceneRecord::error,
            {"", "why the scene did not build (all its jobs fail); `\"\"` when it did"});
    v.field("bad_input", &PlannedSceneRecord::bad_input,
            {"", "whether it did not build because its input (a glTF file, say) is bad"});
    v.field("input_error", &PlannedSceneRecord::input_error,
            {"", "then the input's error, with the file and the place in it; else `\"\"`"});
    v.field("log", &PlannedSceneRecord::log,
            {"", "one line per derived or inferred datum and per decision, as `plan` prints them"});
  }
  bool operator==(const PlannedSceneRecord&) const = default;
};

// One job of the plan.
struct PlannedJobRecord {
  static constexpr RecordDoc kSchema{"PlannedJobRecord", "one job of any shard, in plan order"};

  std::string id;
  std::int64_t index = 0;
  std::string scene, resolution, technique;
  std::string outcome;  // "run", "skip", "fail"
  std::string reason;
  bool bad_input = false;
  double cost = 0;
  int shard = 1;

  template <class V>
  static void describe(V& v) {
    v.field("id", &PlannedJobRecord::id, {"", "the job's id: its record's `job_id`"});
    v.field("index", &PlannedJobRecord::index,
            {"", "its place in the plan, from 0: its record's `job_index`"});
    v.field("scene", &PlannedJobRecord::scene, {"", "the scene variant's name"});
    v.field("resolution", &PlannedJobRecord::resolution, {"", "the resolution's label"});
    v.field("technique", &PlannedJobRecord::technique, {"", "the technique variant's name"});
    v.field("outcome", &PlannedJobRecord::outcome,
            {"",
             "`run`, `skip` or `fail`: its record says `ok` (or `failed`, with what went "
             "wrong while it ran), `skipped` or `failed`"});
    v.field("reason", &PlannedJobRecord::reason,
            {"", "for `skip` and `fail`, the reason its record gives; else `\"\"`"});
    v.field("bad_input", &PlannedJobRecord::bad_input,
            {"", "for `fail`: whether its scene's input is bad"});
    v.field("cost", &PlannedJobRecord::cost, {"", "its estimated cost (docs/scale_out.md)"});
    v.field("shard", &PlannedJobRecord::shard,
            {"", "the shard that runs it, from 1 to `shard_count`"});
  }
  bool operator==(const PlannedJobRecord&) const = default;
};

// plan.json.
struct PlanRecord {
  static constexpr RecordDoc kSchema{"PlanRecord", "a run folder's `plan.json`"};

  int plan_version = kPlanVersion;
  std::string config;  // the config file as given
  std::string name;    // the experiment's name
  int shard_count = 1;
  PlanCounts counts;
  std::vector<PlannedSceneRecord> scenes;
  std::vector<PlannedJobRecord> jobs;

  template <class V>
  static void describe(V& v) {
    v.field("plan_version", &PlanRecord::plan_version,
            {"", "the version of this shape; a reader refuses another"});
    v.field("config", &PlanRecord::config, {"", "the config file, as `run` was given it"});
    v.field("name", &PlanRecord::name, {"", "the experiment's name"});
    v.field("shard_count", &PlanRecord::shard_count,
            {"", "N of `--shard K/N` (or `plan --shards N`); 1 without"});
    v.field("counts", &PlanRecord::counts, {"", "jobs planned each way, over all shards"});
    v.field("scenes", &PlanRecord::scenes, {"", "every scene variant, in config order"});
    v.field("jobs", &PlanRecord::jobs, {"", "every job of every shard, in plan order"});
  }
  // What one member says about another: the version, each job's outcome and
  // shard, its index against its place, the counts against the jobs.
  static void check(const PlanRecord& p, const Fields& f);

  nlohmann::json to_json() const;
  // Throws RecordError naming the JSON pointer of what is wrong.
  static PlanRecord from_json(const nlohmann::json& j);
  bool operator==(const PlanRecord&) const = default;
};

// "" when `a` and `b` plan the same jobs the same way (the same experiment,
// shards, scenes and jobs), whatever path each was given the config by;
// else the first difference, naming both values.
std::string plan_difference(const PlanRecord& a, const PlanRecord& b);

}  // namespace sb::record
