#include "record/scene_record.h"

#include "record/record_json.h"

namespace sb::record {

nlohmann::json SceneRecord::to_json() const { return write_record(*this); }
SceneRecord SceneRecord::from_json(const Fields& f) { return read_record<SceneRecord>(f); }
nlohmann::json PluginRecord::to_json() const { return write_record(*this); }
PluginRecord PluginRecord::from_json(const Fields& f) { return read_record<PluginRecord>(f); }
nlohmann::json TechniqueRecord::to_json() const { return write_record(*this); }
TechniqueRecord TechniqueRecord::from_json(const Fields& f) {
  return read_record<TechniqueRecord>(f);
}

}  // namespace sb::record
