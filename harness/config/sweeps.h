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

namespace sb::config {

// How many variants an entry's parameters sweep to, saturating.
uint64_t sweep_count(const nlohmann::json& params);

// "base/k=5,size=1024" from the explicitly given parameters, in declaration order.
std::string variant_name(const std::string& base, const std::vector<core::ParamSpec>& specs,
                         const nlohmann::json& given);

// The pointer of parameter `key` of one sweep combination `combo` of the
// parameters `given` at `pointer`: the list element it took when `key`
// sweeps (".../params/k/2"), else the member (".../params/k").
std::string swept_pointer(const nlohmann::json& given, const nlohmann::json& combo,
                          const std::string& pointer, const std::string& key);

// resolve_params for one combination of a sweep: an error about a swept
// parameter names the list element the combination took.
core::Params resolve_sweep_combo(const std::vector<core::ParamSpec>& specs,
                                 const nlohmann::json& given, const nlohmann::json& combo,
                                 const std::string& file, const std::string& pointer);

// Refuses an experiment of more than limits.max_jobs jobs.
void check_job_count(const ConfigReader& r, const nlohmann::json& doc,
                     const ExperimentLimits& limits);

}  // namespace sb::config
