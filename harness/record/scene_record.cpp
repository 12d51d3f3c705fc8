#include "record/scene_record.h"

#include <numeric>

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

namespace {

std::int64_t sum_of(const std::map<std::string, std::int64_t>& bytes) {
  return std::accumulate(bytes.begin(), bytes.end(), std::int64_t(0),
                         [](std::int64_t sum, const auto& need) { return sum + need.second; });
}

}  // namespace

void TechniqueRecord::set_gpu_bytes(std::int64_t own,
                                    const std::map<std::string, std::int64_t>& needs) {
  gpu_own_bytes = own;
  gpu_need_bytes = needs;
  gpu_bytes = own + sum_of(needs);
}

std::optional<std::int64_t> TechniqueRecord::gpu_total_bytes() const {
  return gpu_own_bytes ? gpu_bytes : std::nullopt;
}

void TechniqueRecord::check(const TechniqueRecord& t, const Fields& f) {
  if (!t.gpu_own_bytes && !t.gpu_need_bytes) return;  // an older record, or no GPU figures
  if (!t.gpu_own_bytes) f.fail("gpu_need_bytes", "is there without gpu_own_bytes");
  if (!t.gpu_need_bytes) f.fail("gpu_own_bytes", "is there without gpu_need_bytes");
  if (!t.gpu_bytes) f.fail("gpu_own_bytes", "is there without gpu_bytes, their sum");
  const std::int64_t sum = *t.gpu_own_bytes + sum_of(*t.gpu_need_bytes);
  if (*t.gpu_bytes != sum)
    f.fail("gpu_bytes", "is " + std::to_string(*t.gpu_bytes) +
                            ", not gpu_own_bytes + the sum of "
                            "gpu_need_bytes = " +
                            std::to_string(sum));
}

}  // namespace sb::record
