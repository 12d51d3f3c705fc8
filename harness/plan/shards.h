#pragma once
// Splitting a run over N machines (`plan --shards N`, `run --shard K/N`,
// docs/scale_out.md): each PlannedJob's cost and shard. Decided from the
// config alone, never from what building a scene found, so that every
// shard computes the same split on its own: each job costs
//   weight × (1 + 4.5 × megapixels)
// where weight is the technique's (TechniqueInfo::cost_weight, 1 unless its
// plugin says) and 1 stands for what a job pays whatever its resolution
// (set-up, shadow map, compile frame, metrics). Fitted to configs/quick.json
// on the 2-core development VM: a hard shadow map job took 0.47 s at
// 320×240 and 0.83 s at 640×480, so about 0.35 s × (1 + 4.5 × MP).
// Jobs go, costliest first, to the shard with the least cost so far (ties:
// fewer jobs, then the lower shard); equal costs keep the config's order,
// so the split is the same on every machine.
#include <string>
#include <vector>

#include "config/experiment.h"
#include "plan/plan.h"

namespace sb::plan {

struct ShardSpec {
  int index = 1;  // 1-based: "2/4" is the second of four
  int count = 1;
};
// "K/N" with 1 <= K <= N <= 10000; throws std::invalid_argument saying what
// was expected.
ShardSpec parse_shard(const std::string& text);

// The estimated cost of job (resolution, technique variant) of `e`.
double job_cost(const config::Experiment& e, size_t resolution, size_t technique);

// Sets every job's shard, of `shard_count`, from the jobs' costs (make_plan
// calls it); throws std::invalid_argument outside [1, 10000].
void assign_shards(Plan& plan, int shard_count);

// The layout: per shard its job count, cost and share, then its jobs.
std::string describe_shards(const Plan& plan);

}  // namespace sb::plan
