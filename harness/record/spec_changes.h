#pragma once
// Why a finished job runs again: the named settings of its stored spec
// (JobRecord::spec, run/job_identity.h) that differ from today's, as a
// rerun reports them: "reference.adaptive changed (false -> true)".
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::record {

// One "<dotted name> changed (<before> -> <after>)" per setting that differs,
// nested objects compared member by member, in key order; a member on one
// side only is "absent" on the other. Long values are cut to 80 characters,
// SHA-256s (members named *sha256) to their first 12 hex digits. A plugin
// whose hash changed (a rebuilt module: technique.plugin,
// frames.control.plugin) is one change named by its file:
// "plugin my_pcf.so changed (sha256 ab12ab12ab12.. -> cd34cd34cd34..)". A
// file (an object of "sha256" and "reads" only, config/identity.h) is named
// by its `labels` entry (dotted name -> path), else by its dotted name, one
// line for it and one for each file read through it whose content differs:
// "file cube.gltf: content changed (sha256 ab12.. -> cd34..)", "file
// cube.bin of cube.gltf: content changed (...)".
std::vector<std::string> spec_changes(const nlohmann::json& before, const nlohmann::json& after,
                                      const nlohmann::json& labels = nlohmann::json::object());

// "" when `earlier` is kept (its spec_hash is `hash`); else why its job runs
// again: the changed settings (at most three named, then how many more; a
// file parameter's named by the path in `earlier`'s scene or technique), or
// that the record stores no spec (written before records kept theirs).
std::string rerun_reason(const JobRecord& earlier, const nlohmann::json& spec,
                         const std::string& hash);

}  // namespace sb::record
