#include "record/second_reference_record.h"

#include "record/record_json.h"

namespace sb::record {

nlohmann::json SecondReferenceRecord::to_json() const { return write_record(*this); }
SecondReferenceRecord SecondReferenceRecord::from_json(const Fields& f) {
  return read_record<SecondReferenceRecord>(f);
}

}  // namespace sb::record
