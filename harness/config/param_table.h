#pragma once
// Parameter documentation generated from the ParamSpecs themselves, so the
// tables in docs/parameters.md (`shadowbench list --markdown`) cannot drift
// from what the config reader accepts.
#include <string>
#include <vector>

#include "core/params.h"

namespace sb::config {

// What a config may give: "1 … 15, odd", the choices, "a file path,
// relative to the config, required"; with `markdown`, choices in backticks.
std::string accepted_values(const core::ParamSpec& spec, bool markdown);

// `text` as a Markdown table cell: pipes escaped.
std::string markdown_cell(const std::string& text);

// | parameter | type | default | accepted | meaning |, one row per spec.
std::string markdown_param_table(const std::vector<core::ParamSpec>& specs);

}  // namespace sb::config
