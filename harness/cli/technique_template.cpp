#include "cli/technique_template.h"

namespace sb::cli {

const std::vector<TechniqueTemplate>& technique_templates() {
  static const std::vector<TechniqueTemplate> templates = {plugin_api_template()};
  return templates;
}

const TechniqueTemplate* find_technique_template(const std::string& family) {
  for (const TechniqueTemplate& t : technique_templates())
    if (t.family == family) return &t;
  return nullptr;
}

}  // namespace sb::cli
