#pragma once
// The images a run writes into its folder, as the records name them: the
// reference's of one (scene, resolution), which every job's record names,
// and each job's own.
#include <string>

#include "core/image.h"
#include "metrics/job_metrics.h"
#include "metrics/regions.h"
#include "record/job_record.h"
#include "reference/reference.h"
#include "run/runner.h"

namespace sb::run {

// The reference's V, standard error and shaded image, the masks of the
// regions every job shares (and with --gbuffer the G-buffer's), under
// <run_dir>/<rel>; nothing without o.write_images.
record::ImagesRecord write_reference_images(const RunOptions& o, const std::string& rel,
                                            const reference::Result& ref,
                                            const core::ImageF& ref_shaded,
                                            const metrics::Regions& regions,
                                            const core::ImageF& positions,
                                            const core::ImageF& normals);

// The technique's V, its shaded image, its error heat map and its
// soft_union mask, under <run_dir>/jobs/<job id>: the images that need no
// figure of the job, so that they can be written while its figures are
// worked out.
record::ImagesRecord write_job_images(const std::string& run_dir, const std::string& job_id,
                                      const core::ImageF& visibility, const core::ImageF& shaded,
                                      const core::ImageF& ref_visibility,
                                      const metrics::Regions& regions);

// The shaded image's whole-image FLIP map (metrics::measure's `flip_map`)
// in heat-map colours, as <run_dir>/jobs/<job id>/flip_shaded.png.
record::ImagesRecord write_flip_image(const std::string& run_dir, const std::string& job_id,
                                      const core::ImageF& flip_map);

// The pixels of the technique's V (before the attached-shadow mask) that
// fail the visibility check, by kind (metrics::invalid_visibility_image), as
// <run_dir>/jobs/<job id>/invalid.png: the record's images.invalid.
record::ImagesRecord write_invalid_visibility(const std::string& run_dir, const std::string& job_id,
                                              const core::ImageF& visibility);

}  // namespace sb::run
