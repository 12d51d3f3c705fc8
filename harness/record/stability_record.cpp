#include "record/stability_record.h"

#include "record/record_json.h"

namespace sb::record {

nlohmann::json StabilityRecord::to_json() const { return write_record(*this); }
StabilityRecord StabilityRecord::from_json(const Fields& f) {
  return read_record<StabilityRecord>(f);
}

}  // namespace sb::record
