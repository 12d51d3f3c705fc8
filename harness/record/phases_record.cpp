#include "record/phases_record.h"

#include "record/record_json.h"

namespace sb::record {

nlohmann::json PhasesRecord::to_json() const { return write_record(*this); }
PhasesRecord PhasesRecord::from_json(const Fields& f) { return read_record<PhasesRecord>(f); }

}  // namespace sb::record
