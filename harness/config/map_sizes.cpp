#include "config/map_sizes.h"

#include <map>

#include "core/error.h"

namespace sb::config {

using core::InputError;
using core::ParamSpec;

namespace {

struct MapSize {
  const TechniqueVariant* variant;
  std::string param;
  long long texels;
  std::string pointer;  // of the value given, or of the entry for a default
};

std::vector<MapSize> compared_map_sizes(const Experiment& e) {
  std::vector<MapSize> out;
  for (const TechniqueVariant& tv : e.techniques) {
    if (tv.info == nullptr || !tv.unavailable.empty() || tv.own_map_size) continue;
    for (const ParamSpec& spec : tv.info->params) {
      if (!spec.map_size || tv.swept.contains(spec.name)) continue;
      const nlohmann::json& values = tv.params.json();
      if (!values.contains(spec.name) || !values[spec.name].is_number_integer()) continue;
      const bool given = tv.given.is_object() && tv.given.contains(spec.name);
      out.push_back({&tv, spec.name, values[spec.name].get<long long>(),
                     given ? tv.pointer + "/params/" + spec.name : tv.pointer});
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> unequal_map_size_warnings(const Experiment& e) {
  const std::vector<MapSize> sizes = compared_map_sizes(e);
  std::map<long long, std::vector<const MapSize*>> by_size;
  for (const MapSize& s : sizes) by_size[s.texels].push_back(&s);
  if (by_size.size() < 2) return {};
  // The common size: the most variants use it; the largest on a tie.
  auto common = by_size.begin();
  for (auto it = by_size.begin(); it != by_size.end(); ++it)
    if (it->second.size() >= common->second.size()) common = it;
  const std::string common_size = std::to_string(common->first);
  const std::string example = common->second.front()->variant->name;
  const std::string others =
      common->second.size() == 1
          ? example
          : std::to_string(common->second.size()) + " others (" + example + " among them)";
  std::vector<std::string> out;
  for (const MapSize& s : sizes) {
    if (s.texels == common->first) continue;
    std::string message = "technique ";
    message += s.variant->name;
    message += " renders a ";
    message += std::to_string(s.texels);
    message += "-texel map (";
    message += s.param;
    message += ") where ";
    message += others;
    message += " render ";
    message += common_size;
    message += ": their times and errors compare unequal maps; set ";
    message += s.param;
    message += " to ";
    message += common_size;
    message += ", or mark the entry \"own_map_size\": true to keep it knowingly";
    out.push_back(InputError(e.file, s.pointer, message, e.position(s.pointer)).what());
  }
  return out;
}

}  // namespace sb::config
