#pragma once
// What every job of one (scene, resolution) is measured against, made once
// before any job's frames: the G-buffer's points read back, the reference
// at them (and the second one, reference.second_method), the regions, the
// reference shaded, its part of every record and its images.
#include <memory>
#include <optional>
#include <string>

#include "config/experiment.h"
#include "core/image.h"
#include "core/scene.h"
#include "metrics/flip.h"
#include "metrics/prepared_reference.h"
#include "metrics/regions.h"
#include "record/job_record.h"
#include "record/reference_record.h"
#include "reference/reference.h"
#include "run/gbuffer.h"
#include "run/job_identity.h"
#include "run/run_events.h"
#include "run/runner.h"

namespace sb::run {

struct MeasurementBasis {
  core::ImageF positions, normals;  // the G-buffer's
  reference::Settings settings;     // the first reference's
  std::string cache_dir;            // where references are cached; "" when they are not
  reference::Result ref;            // attached shadow applied
  core::ImageF ref_shaded;          // the reference's V, shaded
  // Both, with FLIP's half of each made by the first job that measures.
  std::shared_ptr<const metrics::PreparedReference> prepared;
  metrics::Regions regions;
  record::ReferenceRecord ref_record;
  // reference.second_method's reference, and its record part.
  std::optional<reference::Result> second;
  std::optional<record::ReferenceRecord> second_record;
  std::shared_ptr<const metrics::FlipReference> second_flip;  // FLIP's half of its V
  record::ImagesRecord ref_images;                            // every job's record names them

  // The reference of `scene` (the same one with its light moved, say) at
  // the G-buffer's points, with the first one's settings and cache.
  reference::Result reference_of(const core::Scene& scene) const;
};

// `targets` holds the G-buffer of `scene` (FrameTargets::render_gbuffer);
// shading the reference leaves its V in the visibility target. Tells
// `events` each reference's phase and logs how it was made.
MeasurementBasis make_measurement_basis(const config::Experiment& e, const RunOptions& o,
                                        const EmbreeChoice& embree, RunEvents& events,
                                        const std::string& scene_name, const core::Scene& scene,
                                        const config::Resolution& res, FrameTargets& targets);

}  // namespace sb::run
