#pragma once
// Records with many or all of their members set, for the tests that read
// and write them whole: the round trips and the schema's pointers.
#include <cmath>
#include <limits>
#include <string>

#include "record/job_record.h"
#include "sample_records.h"

namespace sb::test {

inline record::RegionStats region(double rmse) {
  record::RegionStats s;
  s.pixel_count = 1200;
  s.rmse = rmse;
  s.mae = rmse / 2;
  s.max_error = 1.0;
  s.max_x = 17;
  s.max_y = 3;
  s.psnr = -20 * std::log10(rmse);
  s.ssim = 0.75;
  s.frac_over_001 = 0.5;
  s.frac_over_005 = 0.25;
  s.frac_over_01 = 0.125;
  s.nonfinite_count = 2;
  s.mean_signed = -0.01;
  s.flip_mean = rmse / 4;
  return s;
}

// An ok job with every optional member: fine pass timing, G-buffer images,
// a warning, LP_NUM_THREADS, and non-finite numbers.
inline record::JobRecord full_record() {
  record::JobRecord r = test::identity_record("sphere_grid/light_size=2.0", "64x48", "pcf_box/k=3");
  r.scene.params = {{"grid", 9}, {"light_size", 2.0}};
  r.technique.family = "shadow_map";
  r.technique.params = {{"k", 3}, {"size", 1024}};
  record::BuiltScene b;
  b.triangles = 61562;
  b.caster_triangles = 61560;
  b.analytic_casters = 81;
  b.light = {{0, 10, 0}, {0, 0, 0}, {2, 2}, 1.5, 0.53};
  b.camera = {{0, 12.125, 14.5}, {0, 0, 1.875}, 50};
  b.derived = {true, false, true, {"ground"}};
  r.scene.built = b;
  r.host.lp_num_threads = "2";
  r.host.name = "vm";
  r.started_at = "2026-12-01T00:00:00Z";
  r.duration_s = 0.5;
  record::PhasesRecord phases;
  phases.prepare = 0.01;
  phases.frames = 0.4;
  phases.measure = 0.05;
  phases.images = 0.03;
  r.phases_s = phases;
  r.overhead_s = phases.overhead(0.5);
  record::ReferenceRecord ref;
  ref.method = "embree_stratified_packet16";
  ref.spp = 256;
  ref.seed = std::numeric_limits<std::uint64_t>::max();
  ref.embree_isa = "avx2";
  ref.mean_std_error = 0.003;
  ref.estimate_pixels = 700;
  ref.stopped_pixels = 9000;
  ref.mean_stop_bound = 0.0028;
  ref.penumbra_source = "exact";
  ref.penumbra_pixels = 800;
  ref.attached_shadow_pixels = 90;
  ref.horizon_cut_pixels = 40;
  ref.cache_key = "abc";
  ref.seconds = 1.25;
  r.reference = ref;
  r.timing = test::coarse_timing({10, 12, 11}, {4, 5, 4.5});
  test::add_fine_timing(*r.timing, {{"depth", {2, 2.5, 2.25}}, {"lookup", {2.5, 3, 2.75}}});
  r.visibility_check = record::VisibilityCheckRecord{0, 1, 2, double(1e-5f)};
  record::MetricsRecord m;
  m.visibility = {region(0.1), region(0.3), region(0.2)};
  m.shaded = {region(0.05), region(0.15), region(0.1)};
  m.shaded.all.psnr = std::numeric_limits<double>::infinity();
  m.shaded.penumbra.ssim = std::numeric_limits<double>::quiet_NaN();
  m.shaded.soft_union.mean_signed = -std::numeric_limits<double>::infinity();
  r.metrics = m;
  r.warnings = {"reference noise is over half the penumbra RMSE"};
  r.images.visibility = "jobs/x/visibility.exr";
  r.images.shaded = "jobs/x/shaded.png";
  r.images.error_heatmap = "jobs/x/error.png";
  r.images.error_heatmap_full_scale = 0.25;
  r.images.flip_shaded = "jobs/x/flip_shaded.png";
  r.images.reference_visibility = "reference/x/visibility.exr";
  r.images.reference_std_error = "reference/x/std_error.exr";
  r.images.reference_stop_bound = "reference/x/stop_bound.exr";
  r.images.reference_shaded = "reference/x/shaded.png";
  r.images.gbuffer_positions = "reference/x/positions.exr";
  r.images.gbuffer_normals = "reference/x/normals.exr";
  r.images.masks = {{"all", "reference/x/mask_all.png"},
                    {"soft_union", "jobs/x/mask_soft_union.png"}};
  return r;
}

// full_record() with every optional member a record can have set: what
// the schema test holds the schema's pointers to.
inline record::JobRecord every_member_record() {
  record::JobRecord r = full_record();
  r.spec = nlohmann::json{{"frames", {{"control", "none"}}}};
  r.job_index = 4;
  r.shard = "1/2";
  r.reason = "a visibility check failed";
  r.technique.plugin = record::PluginRecord{"shadow_map.so", 812345, std::string(64, 'a'), 1};
  r.technique.set_gpu_bytes(3456, {{"edge_adjacency", 640}});
  r.technique.measured_frame = 32;
  r.host.gl_stack = record::parse_gl_stack("llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 Mesa 22.3.6");
  r.host.env = {{"LP_NUM_THREADS", "2"}};
  r.host.kernel = "6.1.0";
  r.host.cpu_governor = "performance";
  r.host.embree_isa = "avx2";
  r.build.compiler = "GNU 12.2.0";
  r.build.build_type = "Release";
  r.build.cxx_flags = "-O3";
  r.build.driver_sha256 = std::string(64, 'd');
  r.build.core_sha256 = std::string(64, 'c');
  r.build.plugin_api_sha256 = std::string(64, 'p');
  r.session = record::SessionRecord{"0123456789abcdef", "2026-12-07T12:00:00Z", "vm", 0.52,
                                    "fedcba9876543210"};
  r.reference->exact_fallback = "the scene has no exact reference";
  r.reference->adaptive = record::AdaptiveReferenceRecord{16, 0.01, 123.5, 1024, 7, 0.0223};
  record::ControlTiming control;
  control.technique = "none";
  control.frame = record::Series::of({8, 8, 8});
  control.frame_ratio = record::Series::of({1.25, 1.5, 1.375});
  r.timing->control = control;
  r.timing->noise = record::NoiseRecord::judge(*r.timing, 0.05);
  r.timing->noise->load_average_start = 1.25;
  r.timing->noise->load_average_end = 1.5;
  r.timing->noise->usable_cores = 2;
  r.timing->auto_frames = record::AutoFramesRecord{0.03, 10, 1000, 10.0, "target", 0.025, 1.5};
  for (record::ImageMetrics* m : {&r.metrics->visibility, &r.metrics->shaded}) {
    m->geometry = region(0.2);
    m->receivers = region(0.125);
    m->terminator = region(0.25);
    m->near_third = region(0.1);
    m->middle_third = region(0.2);
    m->far_third = region(0.3);
  }
  record::SecondReferenceRecord second;
  second.reference = *r.reference;
  second.visibility = r.metrics->visibility;
  r.second_reference = second;
  r.metrics->flip_shaded = 0.03125;
  record::StabilityRecord stability;
  stability.max_rmse = 0.1;
  stability.flicker_factor = 2;
  stability.stiff_threshold = 1;
  stability.flicker =
      record::FlickerRecord{3, 0.25, 0.01, 0.1, 0.2, 0.05, 1, 0.01, 0.1, 0.2, 0.05, 0.02, 0.03};
  record::SensitivityRecord sensitivity;
  sensitivity.reference_relative = 0.5;
  sensitivity.error = "the perturbed variant failed";
  stability.sensitivity["light_size"] = sensitivity;
  r.stability = stability;
  record::ClassesRecord classes;
  classes.counts = {{{90, 10, 0}, {30, 50, 20}, {0, 0, 100}}};
  r.classes = classes;
  r.child_stderr = {"Segmentation fault"};
  // A failed job's figures ("partial"): an ok record has none, but the
  // schema's every member is here.
  record::PartialRecord partial;
  partial.timing = r.timing;
  partial.gpu_bytes = r.technique.gpu_bytes;
  partial.gpu_own_bytes = r.technique.gpu_own_bytes;
  partial.gpu_need_bytes = r.technique.gpu_need_bytes;
  partial.metrics = r.metrics;
  partial.second_reference = r.second_reference;
  partial.classes = r.classes;
  r.partial = partial;
  r.images.invalid = "jobs/x/invalid.png";
  return r;
}

}  // namespace sb::test
