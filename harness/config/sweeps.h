#pragma once
// List-valued parameters sweep: their cross product (expand_sweeps,
// config/experiment.h), the variants' names, and the count of jobs a config
// makes, known before anything is expanded.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/config_reader.h"
#include "config/experiment.h"

namespace sb {

// How many variants an entry's parameters sweep to, saturating.
uint64_t sweep_count(const nlohmann::json& params);

// "base/k=5,size=1024" from the explicitly given parameters, in declaration order.
std::string variant_name(const std::string& base, const std::vector<ParamSpec>& specs,
                         const nlohmann::json& given);

// Refuses an experiment of more than limits.max_jobs jobs.
void check_job_count(const ConfigReader& r, const nlohmann::json& doc,
                     const ExperimentLimits& limits);

}  // namespace sb
