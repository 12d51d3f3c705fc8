#include "reference/reference.h"

#include <fcntl.h>
#include <sys/file.h>
#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "reference/adaptive.h"
#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/exact_visibility.h"
#include "reference/pixel_rays.h"
#include "reference/stratify.h"
#include "scenes/topology.h"

namespace sb::reference {

namespace {

using detail::Device;
using detail::FlatScene;
using detail::FtzDazScope;

constexpr const char* kMethod = "embree_stratified_packet16";
// Bump whenever the estimate changes for the same inputs (sampling, offsets,
// error estimate): it is part of every cache key.
// 2: horizon test, viewer-facing normals; 3: alpha masks; 4: ray offsets from
// the point and its own triangles, not the scene's radius (ray_offset.h);
// 5: analytic shapes (Mesh::analytic) occlude instead of their meshes and
// join the key; 6: the triangles a point lies on are those within the
// offset's radius of their own bounds (ray_offset.h), not whatever Embree's
// leaves visited, so that the exact reference applies the same test; and
// Embree's robust mode (rays through shared edges no longer slip between the
// triangles, embree_scene.h).
constexpr uint32_t kMethodVersion = 6;
// Bumped whenever the exact reference's answer may change. 2: a point inside
// a closed caster is in its umbra; 3: the same by a segment test, closed
// casters keeping their near side again; 4: the viewpoint offset by Monte
// Carlo's rule (the triangles the point lies on), not by the casters'
// largest coordinate; 5: each closed part (triangles connected through
// shared edges) oriented by its own volume, and a point inside one when it
// winds around the point more than around the light's centre, not by the
// mesh's total volume and the first crossing.
constexpr uint32_t kExactMethodVersion = 5;
// Bumped whenever the adaptive reference's figures may change for the same
// settings. 2: where the proofs apply, an agreeing pilot stops only when
// proven to see the whole light or none of it (sample counts fall, and a
// soft pixel the 5×5 window let through is now refined); 3: the proof of an
// occluded pilot by kExactMethodVersion 5's inside test, and its silhouette
// test over the part the centre's ray crosses, not the whole mesh; 4: the
// pilot only decides, from a stream of its own, and the estimate is fresh
// samples at the level decided (adaptive.h: unbiased), stops without proof
// report the error such stops can hide, and samples count the pilot's; 5:
// the proofs also with alpha-masked casters, each masked triangle whole.
constexpr uint32_t kAdaptiveVersion = 5;
constexpr char kMagic[8] = {'S', 'B', 'R', 'E', 'F', '\r', '\n', '\x1a'};
constexpr uint32_t kFileVersion = 1;

// The settings' device config, or the environment's when they leave it empty.
std::string embree_config_of(const Settings& s) {
  return s.embree_config.empty() ? default_embree_config() : s.embree_config;
}

const char* method_of(const Settings& s) {
  return s.exact ? kExactMethod : s.adaptive ? kAdaptiveMethod : kMethod;
}

void check_inputs(const ImageF& positions, const ImageF& normals, const Settings& s) {
  if (s.spp < 1 || s.spp > (1 << 20))
    throw std::invalid_argument("reference: spp must be in [1, 2^20], got " +
                                std::to_string(s.spp));
  check_embree_config(embree_config_of(s));
  if (s.adaptive && !s.exact) {
    if (const std::string why = detail::adaptive_layout_problem(s.spp, s.pilot_spp); !why.empty())
      throw std::invalid_argument("reference: adaptive sampling: " + why);
    if (!(s.target_std_error > 0.0 && s.target_std_error <= 0.5))
      throw std::invalid_argument("reference: target_std_error must be in (0, 0.5]");
  }
  if (positions.channels != 4)
    throw std::invalid_argument("reference: positions must have 4 channels (xyz, coverage)");
  if (normals.channels < 3)
    throw std::invalid_argument("reference: normals must have at least 3 channels");
  if (positions.width != normals.width || positions.height != normals.height)
    throw std::invalid_argument("reference: positions and normals differ in size");
  if (positions.width < 0 || positions.height < 0 ||
      positions.data.size() != positions.pixel_count() * 4 ||
      normals.data.size() != normals.pixel_count() * size_t(normals.channels))
    throw std::invalid_argument("reference: image data does not match its shape");
}

using detail::covered;

void summarise(Result& r, const ImageF& positions, const Settings& s) {
  double sum = 0, psum = 0, psum2 = 0;
  size_t count = 0, pcount = 0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    if (!covered(positions, i)) continue;
    sum += r.std_error.data[i];
    ++count;
    const float v = r.visibility.data[i];
    if (v > 0.0f && v < 1.0f) {
      psum += r.std_error.data[i];
      psum2 += double(r.std_error.data[i]) * double(r.std_error.data[i]);
      ++pcount;
    }
  }
  r.mean_std_error = count ? sum / double(count) : 0.0;
  r.penumbra_mean_std_error = pcount ? psum / double(pcount) : 0.0;
  r.penumbra_rms_std_error = pcount ? std::sqrt(psum2 / double(pcount)) : 0.0;
  double samples = 0;
  float most = 0;
  for (size_t i = 0; i < positions.pixel_count() && !r.samples.data.empty(); ++i) {
    if (!covered(positions, i)) continue;
    samples += r.samples.data[i];
    most = std::max(most, r.samples.data[i]);
  }
  r.mean_spp = count ? samples / double(count) : 0.0;
  r.max_spp = int(most);
  if (r.method == kAdaptiveMethod) {
    r.unproven_stops = int64_t(detail::unproven_stops(r.samples, r.std_error, s.pilot_spp));
    r.stop_bias_bound = r.unproven_stops > 0 ? detail::stop_bias_bound(s.pilot_spp) : 0.0;
  }
}

// spp on every covered pixel, 0 elsewhere: a uniform reference's samples.
ImageF uniform_samples(const ImageF& positions, int spp) {
  ImageF out(positions.width, positions.height, 1, 0.0f);
  for (size_t i = 0; i < positions.pixel_count(); ++i)
    if (covered(positions, i)) out.data[i] = float(spp);
  return out;
}

// A segment light is stratified along its one axis (stratify.h); rectangles
// and points keep the square cells.
detail::Strata strata_of(const AreaLight& light) {
  if (!light.is_segment()) return detail::Strata::Square;
  return light.width() > 0.0f ? detail::Strata::AlongS : detail::Strata::AlongT;
}

// Every covered pixel's spp samples, in trace order (4×4 blocks of strata,
// one packet each; stratify.h).
void trace(const detail::RaySetup& setup, Result& r) {
  const detail::Layout& layout = setup.layout;
  const ImageF& positions = setup.positions;
  const int width = positions.width;
  const size_t spp = size_t(layout.spp);
  std::vector<uint32_t> all(spp);
  for (size_t i = 0; i < spp; ++i) all[i] = uint32_t(i);

  tbb::parallel_for(tbb::blocked_range2d<int>(0, positions.height, 8, 0, width, 8),
                    [&](const tbb::blocked_range2d<int>& tile) {
                      FtzDazScope ftz;
                      detail::PixelRays rays(setup);
                      std::vector<uint8_t> reached(spp), visible(spp);
                      for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
                        for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                          const size_t pix = size_t(y) * size_t(width) + size_t(x);
                          if (!covered(positions, pix)) continue;  // V = 1, error 0 preset
                          rays.start(pix);
                          rays.trace(all.data(), spp, reached.data());
                          size_t count = 0;
                          for (size_t i = 0; i < spp; ++i) {
                            visible[layout.order[i].cell] = reached[i];
                            count += reached[i];
                          }
                          r.visibility.data[pix] = float(double(count) / double(spp));
                          r.std_error.data[pix] =
                              float(std::sqrt(detail::stratified_variance(visible.data(), layout)));
                        }
                    });
}

// ---- cache file -----------------------------------------------------------

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool get(T& v) {
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get(std::string& s, uint32_t max_len) {
    uint32_t n = 0;
    if (!get(n) || n > max_len || bytes_.size() - pos_ < n) return false;
    s.assign(bytes_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool get(std::vector<float>& v, size_t n) {
    if ((bytes_.size() - pos_) / sizeof(float) < n) return false;
    v.resize(n);
    std::memcpy(v.data(), bytes_.data() + pos_, n * sizeof(float));
    pos_ += n * sizeof(float);
    return true;
  }
  size_t pos() const { return pos_; }

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

std::string serialise(const Result& r) {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kFileVersion);
  put(out, int32_t(r.visibility.width));
  put(out, int32_t(r.visibility.height));
  put(out, int32_t(r.spp));
  put(out, r.seed);
  put(out, uint32_t(r.method.size()));
  out += r.method;
  put(out, uint32_t(r.cache_key.size()));
  out += r.cache_key;
  out.append(reinterpret_cast<const char*>(r.visibility.data.data()),
             r.visibility.data.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(r.std_error.data.data()),
             r.std_error.data.size() * sizeof(float));
  if (r.method == kAdaptiveMethod)  // uniform files stay as they were
    out.append(reinterpret_cast<const char*>(r.samples.data.data()),
               r.samples.data.size() * sizeof(float));
  put(out, fnv1a64(out));
  return out;
}

// Returns false for anything that is not exactly the file get() would write.
bool deserialise(const std::string& bytes, const std::string& key, const ImageF& positions,
                 const Settings& s, Result& r) {
  if (bytes.size() < sizeof(kMagic) + sizeof(uint64_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    return false;
  uint64_t stored_sum = 0;
  std::memcpy(&stored_sum, bytes.data() + bytes.size() - sizeof(stored_sum), sizeof(stored_sum));
  if (stored_sum != fnv1a64(std::string_view(bytes.data(), bytes.size() - sizeof(stored_sum))))
    return false;
  Reader in(bytes);
  char magic[sizeof(kMagic)];
  uint32_t version = 0;
  int32_t w = 0, h = 0, spp = 0;
  uint64_t seed = 0;
  std::string method, stored_key;
  if (!in.get(magic) || !in.get(version) || version != kFileVersion || !in.get(w) || !in.get(h) ||
      !in.get(spp) || !in.get(seed) || !in.get(method, 256) || !in.get(stored_key, 256))
    return false;
  if (w != positions.width || h != positions.height || spp != (s.exact ? 0 : s.spp) ||
      seed != s.seed || method != method_of(s) || stored_key != key)
    return false;
  const size_t n = positions.pixel_count();
  ImageF vis(w, h, 1), se(w, h, 1);
  if (!in.get(vis.data, n) || !in.get(se.data, n)) return false;
  ImageF samples(w, h, 1);
  if (s.adaptive && !s.exact) {
    if (!in.get(samples.data, n)) return false;
    for (float v : samples.data)  // the pilot's samples come on top of the estimate's
      if (!(v >= 0.0f && v <= float(s.spp + s.pilot_spp))) return false;
  } else {
    samples = uniform_samples(positions, s.exact ? 0 : s.spp);
  }
  if (in.pos() + sizeof(uint64_t) != bytes.size()) return false;
  for (size_t i = 0; i < n; ++i)
    if (!(vis.data[i] >= 0.0f && vis.data[i] <= 1.0f && se.data[i] >= 0.0f && se.data[i] <= 1.0f))
      return false;
  r.visibility = std::move(vis);
  r.std_error = std::move(se);
  r.samples = std::move(samples);
  return true;
}

bool read_file(const std::filesystem::path& path, std::string& bytes) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::ostringstream ss;
  ss << f.rdbuf();
  if (f.bad()) return false;
  bytes = std::move(ss).str();
  return true;
}

// An exclusive flock on a cache key's lock file, held while its reference is
// computed; the kernel drops it when the process dies. The file stays (a
// removed lock file could be locked by two processes at once).
class KeyLock {
 public:
  explicit KeyLock(const std::filesystem::path& file)
      : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0)
      throw JobError("reference cache: cannot open " + file.string() + ": " + std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0)
      if (errno != EINTR) {
        const int err = errno;
        ::close(fd_);
        throw JobError("reference cache: cannot lock " + file.string() + ": " + std::strerror(err));
      }
  }
  ~KeyLock() { ::close(fd_); }
  KeyLock(const KeyLock&) = delete;
  KeyLock& operator=(const KeyLock&) = delete;

 private:
  int fd_;
};

void hash_image(Hasher& h, const ImageF& img) {
  h.add(int32_t(img.width)).add(int32_t(img.height)).add(int32_t(img.channels));
  h.add(uint64_t(img.data.size()));
  h.add(img.data.data(), img.data.size() * sizeof(float));
}

void hash_vec3(Hasher& h, const glm::vec3& v) { h.add(v.x).add(v.y).add(v.z); }

// Per mesh, whether it is a closed caster (ExactVisibility's constructor).
// An alpha-masked mesh never is: its mask cuts holes in it.
std::vector<bool> closed_casters(const Scene& scene) {
  std::vector<bool> closed;
  for (const Mesh& m : scene.meshes)
    closed.push_back(m.casts_shadow && !m.double_sided && !m.alpha_tested() &&
                     analyse_topology(m).closed());
  return closed;
}

// Whether the adaptive reference's proofs (adaptive.h) hold for the scene's
// casters: a rectangular light, and every caster inside its triangles. An
// alpha-masked caster is (its mask only takes parts away), so "no triangle
// meets the pyramid" still proves a pilot lit, and, never closed, it proves
// none occluded. An analytic shape bulges out of its triangles.
bool proofs_hold(const Scene& scene) {
  if (scene.light.is_segment() || scene.light.is_point()) return false;
  return std::none_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) {
    return m.casts_shadow && m.analytic.kind != AnalyticShape::Kind::None;
  });
}

}  // namespace

Result compute(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
               const Settings& s) {
  check_inputs(positions, geometric_normals, s);
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    if (!covered(positions, i)) continue;
    const float* p = &positions.data[i * 4];
    const float* n = &geometric_normals.data[i * size_t(geometric_normals.channels)];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) ||
        !std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]))
      throw std::invalid_argument("reference: non-finite position or normal at pixel (" +
                                  std::to_string(i % size_t(positions.width)) + ", " +
                                  std::to_string(i / size_t(positions.width)) + ")");
  }

  if (s.exact) {
    const std::string why = ExactVisibility::unsupported_reason(scene);
    if (!why.empty()) {
      Settings sampled = s;
      sampled.exact = false;
      Result r = compute(scene, positions, geometric_normals, sampled);
      r.exact_fallback = why;
      return r;
    }
    Result r;
    r.seed = s.seed;
    r.method = kExactMethod;
    const auto t0 = std::chrono::steady_clock::now();
    // Closed casters keep only the triangles that face the point, part by
    // part (exact_visibility.h): right whichever way each part winds.
    const ExactVisibility exact(scene, closed_casters(scene));
    r.visibility = exact.image(positions, geometric_normals);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.std_error = ImageF(positions.width, positions.height, 1, 0.0f);
    r.samples = ImageF(positions.width, positions.height, 1, 0.0f);
    summarise(r, positions, s);
    return r;
  }

  Result r;
  r.visibility = ImageF(positions.width, positions.height, 1, 1.0f);
  r.std_error = ImageF(positions.width, positions.height, 1, 0.0f);
  r.spp = s.spp;
  r.seed = s.seed;
  r.method = kMethod;
  r.isa = resolve_isa(embree_config_of(s));

  const auto t0 = std::chrono::steady_clock::now();
  {
    Device device(r.isa);
    FlatScene casters(
        device, scene, [](const Mesh& m) { return m.casts_shadow; }, /*analytic_shapes=*/true);
    const detail::Strata strata = strata_of(scene.light);
    const detail::Layout layout = detail::make_layout(s.spp, strata);
    const detail::RaySetup setup(scene, casters, layout, positions, geometric_normals, s.seed);
    if (s.adaptive) {
      // The proofs that an agreeing pilot missed nothing; the one for
      // occluded pilots needs to know which casters are closed.
      std::optional<ExactVisibility> whole_light;
      if (proofs_hold(scene)) whole_light.emplace(scene, closed_casters(scene));
      detail::AdaptiveImages a = detail::trace_adaptive(
          setup, strata, s.pilot_spp, s.target_std_error, whole_light ? &*whole_light : nullptr);
      r.visibility = std::move(a.visibility);
      r.std_error = std::move(a.std_error);
      r.samples = std::move(a.samples);
      r.method = kAdaptiveMethod;
    } else {
      trace(setup, r);
      r.samples = uniform_samples(positions, s.spp);
    }
    device.check("rtcOccluded16");
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  summarise(r, positions, s);
  return r;
}

std::string method_id(const Settings& s) {
  std::string sampled =
      std::string(s.adaptive ? kAdaptiveMethod : kMethod) + "/" + std::to_string(kMethodVersion);
  if (s.adaptive) sampled += "." + std::to_string(kAdaptiveVersion);
  sampled += std::string(" on Embree ") + RTC_VERSION_STRING;
  if (!s.exact) return sampled;
  return std::string(kExactMethod) + "/" + std::to_string(kExactMethodVersion) + ", else " +
         sampled;
}

std::string cache_key(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
                      const Settings& s) {
  Hasher h;
  h.add("shadowbench.reference").add(method_of(s)).add(kMethodVersion);
  if (s.exact) {
    h.add(kExactMethodVersion);
  } else {
    h.add(RTC_VERSION_STRING).add(resolve_isa(embree_config_of(s)));
    h.add(int32_t(s.spp)).add(s.seed);
    if (s.adaptive) h.add(int32_t(s.pilot_spp)).add(s.target_std_error).add(kAdaptiveVersion);
  }
  hash_vec3(h, scene.light.center);
  hash_vec3(h, scene.light.half_u);
  hash_vec3(h, scene.light.half_v);
  // Only a segment's key carries its layout, so that keys from before it was
  // stratified along its axis (and from before the exact reference did
  // segments) never match, while rectangles' and points' keys stay as they were.
  if (scene.light.is_segment()) h.add("light_strata:segment_1d");
  uint64_t casters = 0;
  for (const Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    ++casters;
    h.add(uint64_t(m.positions.size()));
    h.add(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    h.add(uint64_t(m.indices.size()));
    h.add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
    h.add(m.alpha_tested());
    if (m.alpha_tested()) {  // the mask decides which rays pass
      const TextureImage& t = scene.textures.at(size_t(m.base_color_texture));
      h.add(m.alpha_cutoff).add(int32_t(t.width)).add(int32_t(t.height));
      h.add(m.uvs.data(), m.uvs.size() * sizeof(glm::vec2));
      h.add(t.rgba.data(), t.rgba.size());
    }
    // The shape the reference traces instead of the triangles, if any.
    h.add(m.analytic.kind);
    if (m.analytic.has()) {
      hash_vec3(h, m.analytic.center);
      h.add(m.analytic.radius);
    }
  }
  h.add(casters);
  hash_image(h, positions);
  hash_image(h, geometric_normals);
  return h.hex();
}

Result get(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
           const Settings& s, const std::string& cache_dir) {
  check_inputs(positions, geometric_normals, s);
  if (s.exact) {
    const std::string why = ExactVisibility::unsupported_reason(scene);
    if (!why.empty()) {
      Settings sampled = s;
      sampled.exact = false;
      Result r = get(scene, positions, geometric_normals, sampled, cache_dir);
      r.exact_fallback = why;
      return r;
    }
  }
  const std::string key = cache_key(scene, positions, geometric_normals, s);
  const std::filesystem::path path = std::filesystem::path(cache_dir) / (key + ".sbref");
  const auto from_cache = [&]() -> std::optional<Result> {
    std::string bytes;
    Result cached;
    if (!read_file(path, bytes) || !deserialise(bytes, key, positions, s, cached))
      return std::nullopt;
    cached.spp = s.exact ? 0 : s.spp;
    cached.seed = s.seed;
    cached.method = method_of(s);
    cached.isa = s.exact ? "" : resolve_isa(embree_config_of(s));
    cached.from_cache = true;
    cached.cache_key = key;
    summarise(cached, positions, s);
    return cached;
  };
  if (auto cached = from_cache()) return std::move(*cached);

  std::error_code ec;
  std::filesystem::create_directories(cache_dir, ec);
  if (ec) throw JobError("reference cache: cannot create " + cache_dir + ": " + ec.message());
  // One computation per key across processes (the shards of a run sharing
  // --cache-dir): the first to take the key's lock computes, the others
  // wait and then read its file.
  const KeyLock lock(std::filesystem::path(cache_dir) / (key + ".lock"));
  if (auto cached = from_cache()) return std::move(*cached);
  Result r = compute(scene, positions, geometric_normals, s);
  r.cache_key = key;
  write_file_atomically(path.string(), serialise(r), "reference cache: ");
  return r;
}

GBuffer trace_gbuffer(const Scene& scene, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("trace_gbuffer: empty image");
  GBuffer g{ImageF(width, height, 4, 0.0f), ImageF(width, height, 3, 0.0f)};
  Device device(resolve_isa(default_embree_config()));
  FlatScene all(device, scene, [](const Mesh&) { return true; });
  if (all.empty()) return g;

  const Camera& cam = scene.camera;
  const glm::mat3 to_world(glm::inverse(cam.view()));
  const float tan_half = std::tan(glm::radians(cam.fov_y_degrees) * 0.5f);
  const float aspect = float(width) / float(height);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    FtzDazScope ftz;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width; ++x) {
        const float ndc_x = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
        const float ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(height);
        // z = -1 in view space, so t is the view-space depth.
        const glm::vec3 d =
            to_world * glm::vec3(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0f);
        RTCRayHit rh;
        rh.ray.org_x = cam.eye.x;
        rh.ray.org_y = cam.eye.y;
        rh.ray.org_z = cam.eye.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = cam.near_plane;
        rh.ray.tfar = cam.far_plane;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xffffffffu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(all.get(), &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const Mesh& m = scene.meshes[all.mesh_of_geometry[rh.hit.geomID]];
        const size_t tri = size_t(rh.hit.primID) * 3;
        const glm::vec3 v0 = m.positions[m.indices[tri]], v1 = m.positions[m.indices[tri + 1]],
                        v2 = m.positions[m.indices[tri + 2]];
        // Interpolate on the triangle rather than org + t*dir: the point lies on it.
        const glm::vec3 p = (1.0f - rh.hit.u - rh.hit.v) * v0 + rh.hit.u * v1 + rh.hit.v * v2;
        const glm::vec3 c = glm::cross(v1 - v0, v2 - v0);
        const float len = glm::length(c);
        glm::vec3 n = len > 0.0f ? c / len : glm::vec3(0.0f);
        // Facing the viewer, as the rasterised G-buffer's (the seen side).
        if (glm::dot(n, d) > 0.0f) n = -n;
        float* pp = &g.positions.at(x, y);
        pp[0] = p.x;
        pp[1] = p.y;
        pp[2] = p.z;
        pp[3] = 1.0f;
        float* np = &g.normals.at(x, y);
        np[0] = n.x;
        np[1] = n.y;
        np[2] = n.z;
      }
  });
  device.check("rtcIntersect1");
  return g;
}

}  // namespace sb::reference
