#pragma once
// KHR_debug plumbing: driver messages of type ERROR are collected, and
// throw_if_errors() turns them (and glGetError) into a JobError with the
// driver's own words, so a GL mistake fails the job that made it.
#include <string>
#include <vector>

namespace sb::gl {

void enable_debug_output();
// Messages collected since the last call, cleared on return.
std::vector<std::string> take_debug_errors();
// Throws JobError("<where>: <driver message>") if GL reported an error.
void throw_if_errors(const std::string& where);

}  // namespace sb::gl
