#include "record/reference_record.h"

#include "record/record_json.h"

namespace sb::record {

nlohmann::json ReferenceRecord::to_json() const { return write_record(*this); }
ReferenceRecord ReferenceRecord::from_json(const Fields& f) {
  return read_record<ReferenceRecord>(f);
}

}  // namespace sb::record
