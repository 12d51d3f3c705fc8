#include "record/phases_record.h"

namespace sb {

nlohmann::json PhasesRecord::to_json() const {
  return {{"prepare", json_number(prepare)},
          {"frames", json_number(frames)},
          {"measure", json_number(measure)},
          {"images", json_number(images)},
          {"stability", json_number(stability)}};
}

PhasesRecord PhasesRecord::from_json(const Fields& f) {
  PhasesRecord p;
  p.prepare = f.get<double>("prepare");
  p.frames = f.get<double>("frames");
  p.measure = f.get<double>("measure");
  p.images = f.get<double>("images");
  p.stability = f.get<double>("stability");
  return p;
}

}  // namespace sb
