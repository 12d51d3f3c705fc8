#include "plan/shards.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace sb::plan {

using config::Experiment;
using config::Resolution;
using config::TechniqueVariant;

namespace {

// A job's cost at zero pixels, and per megapixel, in units of the first
// (plan/shards.h).
constexpr double kFixedCost = 1.0;
constexpr double kCostPerMegapixel = 4.5;
constexpr int kMaxShards = 10000;

int parse_positive(const std::string& text, const std::string& all) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw std::invalid_argument(
        "expected K/N, two whole numbers with 1 <= K <= N <= 10000, found '" + all + "'");
  return v;
}

}  // namespace

ShardSpec parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos)
    throw std::invalid_argument(
        "expected K/N, two whole numbers with 1 <= K <= N <= 10000, found '" + text + "'");
  ShardSpec s{parse_positive(text.substr(0, slash), text),
              parse_positive(text.substr(slash + 1), text)};
  if (s.index < 1 || s.count < 1 || s.index > s.count || s.count > kMaxShards)
    throw std::invalid_argument(
        "expected K/N, two whole numbers with 1 <= K <= N <= 10000, found '" + text + "'");
  return s;
}

double job_cost(const Experiment& e, size_t resolution, size_t technique) {
  const TechniqueVariant& tv = e.techniques[technique];
  const Resolution& res = e.resolutions[resolution];
  const double megapixels = double(res.width) * double(res.height) / 1e6;
  const double weight = tv.info->cost_weight ? tv.info->cost_weight(tv.params) : 1.0;
  return weight * (kFixedCost + kCostPerMegapixel * megapixels);
}

void assign_shards(Plan& plan, int shard_count) {
  if (shard_count < 1 || shard_count > kMaxShards)
    throw std::invalid_argument("shard count out of [1, 10000]");
  std::vector<PlannedJob>& jobs = plan.jobs;
  plan.shard_count = shard_count;
  std::vector<size_t> order(jobs.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return jobs[a].cost > jobs[b].cost; });
  std::vector<double> load(size_t(shard_count), 0.0);
  std::vector<size_t> count(size_t(shard_count), 0);
  for (size_t j : order) {
    size_t best = 0;
    for (size_t k = 1; k < load.size(); ++k)
      if (load[k] < load[best] || (load[k] == load[best] && count[k] < count[best])) best = k;
    load[best] += jobs[j].cost;
    ++count[best];
    jobs[j].shard = int(best) + 1;
  }
}

std::string describe_shards(const Plan& plan) {
  const std::vector<PlannedJob>& jobs = plan.jobs;
  const int shard_count = plan.shard_count;
  double total = 0;
  for (const auto& j : jobs) total += j.cost;
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu jobs in %d shards (cost: technique weight x (1 + 4.5 x megapixels))\n",
                jobs.size(), shard_count);
  out += line;
  for (int k = 1; k <= shard_count; ++k) {
    double cost = 0;
    size_t n = 0;
    for (const auto& j : jobs)
      if (j.shard == k) {
        cost += j.cost;
        ++n;
      }
    std::snprintf(line, sizeof line, "\nshard %d/%d: %zu jobs, cost %.2f (%.1f%%)\n", k,
                  shard_count, n, cost, total > 0 ? 100.0 * cost / total : 0.0);
    out += line;
    for (const auto& j : jobs)
      if (j.shard == k) {
        std::snprintf(line, sizeof line, "  %8.2f  ", j.cost);
        out += line + j.id + "\n";
      }
  }
  return out;
}

}  // namespace sb::plan
