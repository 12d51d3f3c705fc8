#include "config/unread_params.h"

#include <algorithm>

#include "core/error.h"

namespace sb::config {

using core::InputError;
using core::Params;
using core::ParamSpec;
using plugin::TechniqueInfo;

std::vector<std::string> unread_parameters(const TechniqueInfo& info, const Params& params) {
  const Params fresh(params.json());  // whatever was read before (info.check) does not count
  try {
    (void)info.create(fresh);
  } catch (const std::exception&) {
    return {};
  }
  const std::vector<std::string> unread = fresh.unread();
  std::vector<std::string> out;
  for (const ParamSpec& spec : info.params)
    if (std::find(unread.begin(), unread.end(), spec.name) != unread.end())
      out.push_back(spec.name);
  return out;
}

std::vector<std::string> unread_parameter_warnings(const Experiment& e) {
  std::vector<std::string> out;
  for (const TechniqueVariant& tv : e.techniques)
    for (const std::string& name : unread_parameters(*tv.info, tv.params))
      out.push_back(InputError(e.file, tv.pointer,
                               "technique " + tv.name + ": parameter '" + name + "' of " +
                                   tv.info->name +
                                   " is declared but never read by its factory or constructor",
                               e.position(tv.pointer))
                        .what());
  return out;
}

}  // namespace sb::config
