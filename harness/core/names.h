#pragma once
// File names and job ids made from labels a user wrote (scene and technique
// variant names, which carry sweep values such as file paths).
//
// A name made only of letters, digits and . _ = , / - (no "--" or "__", no
// '-' beside a '/', not starting with '.', at most 96 characters) maps
// readably and one-to-one: '/' becomes "--", ',' becomes '+'. Anything else
// (other characters, a NUL, non-UTF-8 bytes, a leading "..", a long name) is
// mapped the same way with '-' for the other characters, cut to 64
// characters, and given a '~' and 12 hex digits of a hash of the whole name,
// so distinct names never share a file and no name makes a hidden file or
// leaves its folder. The result is at most 77 bytes.
#include <string>

namespace sb::core {

std::string file_safe(const std::string& name);

// scene__resolution__technique, each part file_safe: one record file per job.
std::string job_id(const std::string& scene_variant, const std::string& resolution,
                   const std::string& technique_variant);

}  // namespace sb::core
