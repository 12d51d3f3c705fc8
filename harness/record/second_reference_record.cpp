#include "record/second_reference_record.h"

namespace sb {

nlohmann::json SecondReferenceRecord::to_json() const {
  return {{"reference", reference.to_json()}, {"visibility", visibility.to_json()}};
}

SecondReferenceRecord SecondReferenceRecord::from_json(const Fields& f) {
  return {ReferenceRecord::from_json(f.object("reference")),
          ImageMetrics::from_json(f.object("visibility"))};
}

}  // namespace sb
