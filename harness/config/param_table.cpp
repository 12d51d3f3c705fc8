#include "config/param_table.h"

#include <cstdio>

namespace sb::config {

using core::ParamSpec;
using core::ParamType;
using core::to_string;

namespace {

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

// Pipes would end a Markdown table cell.
std::string markdown_cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string accepted_values(const ParamSpec& p, bool markdown) {
  const std::string quote = markdown ? "`" : "";
  switch (p.type) {
    case ParamType::Int:
    case ParamType::Float: {
      std::string range = number(p.min) + " … " + number(p.max);
      if (!p.rule_doc.empty()) range += ", " + p.rule_doc;
      if (p.sentinel) range += "; " + number(*p.sentinel) + " = chosen automatically";
      if (p.map_size) range += "; a map size, equal across compared techniques (config.md)";
      return range;
    }
    case ParamType::Choice: {
      std::string list;
      for (const auto& c : p.choices) {
        if (!list.empty()) list += ", ";
        list += quote;
        list += c;
        list += quote;
      }
      return list;
    }
    case ParamType::Bool:
      return "true, false";
    case ParamType::String:
      if (!p.is_path) return "text";
      return p.default_value == "" ? "a file path, relative to the config, required"
                                   : "a file path, relative to the config";
  }
  return "";
}

std::string markdown_param_table(const std::vector<ParamSpec>& specs) {
  if (specs.empty()) return "No parameters.\n";
  std::string out = "| parameter | type | default | accepted | meaning |\n|---|---|---|---|---|\n";
  for (const auto& p : specs)
    out += "| `" + p.name + "` | " + to_string(p.type) + " | `" +
           markdown_cell(p.default_value.dump()) + "` | " +
           markdown_cell(accepted_values(p, true)) + " | " + markdown_cell(p.doc) + " |\n";
  return out;
}

}  // namespace sb::config
