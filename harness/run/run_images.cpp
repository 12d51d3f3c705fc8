#include "run/run_images.h"

#include <tbb/parallel_invoke.h>

#include <filesystem>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"

namespace sb::run {

using core::ImageF;
using record::ImagesRecord;

namespace fs = std::filesystem;

namespace {

constexpr float kHeatmapFullScale = 0.25f;

}  // namespace

ImagesRecord write_reference_images(const RunOptions& o, const std::string& rel,
                                    const reference::Result& ref, const ImageF& ref_shaded,
                                    const metrics::Regions& regions, const ImageF& positions,
                                    const ImageF& normals) {
  ImagesRecord images;
  if (!o.write_images) return images;
  const fs::path dir = fs::path(o.run_dir) / rel;
  core::make_own_folder(o.run_dir, rel);
  metrics::io::write_exr((dir / "visibility.exr").string(), ref.visibility);
  metrics::io::write_exr((dir / "std_error.exr").string(), ref.std_error);
  metrics::io::write_exr((dir / "stop_bound.exr").string(), ref.stop_bound);
  metrics::io::write_png((dir / "shaded.png").string(), ref_shaded);
  images.reference_visibility = rel + "/visibility.exr";
  images.reference_std_error = rel + "/std_error.exr";
  images.reference_stop_bound = rel + "/stop_bound.exr";
  images.reference_shaded = rel + "/shaded.png";
  // Named as the record's metrics.visibility regions; soft_union is each job's own.
  for (const metrics::RegionMask& r : regions.masks) {
    if (r.per_job) continue;
    const std::string file = "mask_" + r.key + ".png";
    metrics::io::write_mask_png((dir / file).string(), r.mask, ref.visibility.width,
                                ref.visibility.height);
    images.masks[r.key] = (fs::path(rel) / file).generic_string();
  }
  if (o.write_gbuffer) {
    metrics::io::write_exr((dir / "positions.exr").string(), positions);
    metrics::io::write_exr((dir / "normals.exr").string(), normals);
    images.gbuffer_positions = rel + "/positions.exr";
    images.gbuffer_normals = rel + "/normals.exr";
  }
  return images;
}

// A one-channel map in [0, 1] in the heat-map colours (full scale 1).
ImageF heat_colours(const ImageF& map) {
  ImageF out(map.width, map.height, 3);
  for (std::size_t p = 0; p < map.pixel_count(); ++p)
    metrics::heatmap_colour(map.data[p], &out.data[p * 3]);
  return out;
}

ImagesRecord write_job_images(const std::string& run_dir, const std::string& job_id,
                              const ImageF& visibility, const ImageF& shaded,
                              const ImageF& ref_visibility, const metrics::Regions& regions) {
  const std::string rel = "jobs/" + job_id;
  const fs::path dir = fs::path(run_dir) / rel;
  core::make_own_folder(run_dir, rel);
  // Four files at once: no frame runs now, and one file's encoding keeps
  // one core busy (zlib), so the job's images take about half the time.
  tbb::parallel_invoke(
      [&] {
        metrics::io::write_mask_png((dir / "mask_soft_union.png").string(),
                                    metrics::soft_union_of(visibility, regions), visibility.width,
                                    visibility.height);
      },
      [&] { metrics::io::write_exr((dir / "visibility.exr").string(), visibility); },
      [&] { metrics::io::write_png((dir / "shaded.png").string(), shaded); },
      [&] {
        metrics::io::write_png(
            (dir / "error.png").string(),
            metrics::error_heatmap(
                metrics::with_unmeasured_from(visibility, ref_visibility, regions.measured),
                ref_visibility, kHeatmapFullScale));
      });
  ImagesRecord images;
  images.visibility = rel + "/visibility.exr";
  images.shaded = rel + "/shaded.png";
  images.error_heatmap = rel + "/error.png";
  images.error_heatmap_full_scale = kHeatmapFullScale;
  images.masks["soft_union"] = rel + "/mask_soft_union.png";
  return images;
}

ImagesRecord write_flip_image(const std::string& run_dir, const std::string& job_id,
                              const ImageF& flip_map) {
  const std::string rel = "jobs/" + job_id;
  core::make_own_folder(run_dir, rel);
  metrics::io::write_png((fs::path(run_dir) / rel / "flip_shaded.png").string(),
                         heat_colours(flip_map));
  ImagesRecord images;
  images.flip_shaded = rel + "/flip_shaded.png";
  return images;
}

ImagesRecord write_invalid_visibility(const std::string& run_dir, const std::string& job_id,
                                      const ImageF& visibility) {
  const std::string rel = "jobs/" + job_id;
  const fs::path dir = fs::path(run_dir) / rel;
  core::make_own_folder(run_dir, rel);
  metrics::io::write_png((dir / "invalid.png").string(),
                         metrics::invalid_visibility_image(visibility));
  ImagesRecord images;
  images.invalid = rel + "/invalid.png";
  return images;
}

}  // namespace sb::run
