#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "core/error.h"
#include "reference/embree_isa.h"
#include "reference/reference.h"
#include "test_scenes.h"

namespace {

namespace fs = std::filesystem;
namespace ref = sb::reference;

class referenceCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sb_reference_cache_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(std::random_device{}()));
    scene_ = sbtest::sphere_over_plane();
    g_ = ref::trace_gbuffer(scene_, 24, 18);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  ref::Result get(const ref::Settings& s = {16, 1}) {
    return ref::get(scene_, g_.positions, g_.normals, s, dir_.string());
  }
  std::string key(const sb::core::Scene& scene, const ref::Settings& s = {16, 1}) const {
    return ref::cache_key(scene, g_.positions, g_.normals, s);
  }
  fs::path file(const std::string& key) const { return dir_ / (key + ".sbref"); }

  static void expect_same(const ref::Result& a, const ref::Result& b) {
    ASSERT_EQ(a.visibility.data.size(), b.visibility.data.size());
    const size_t bytes = a.visibility.data.size() * sizeof(float);
    EXPECT_EQ(std::memcmp(a.visibility.data.data(), b.visibility.data.data(), bytes), 0);
    EXPECT_EQ(std::memcmp(a.std_error.data.data(), b.std_error.data.data(), bytes), 0);
    EXPECT_EQ(a.mean_std_error, b.mean_std_error);
    EXPECT_EQ(a.penumbra_mean_std_error, b.penumbra_mean_std_error);
    EXPECT_EQ(a.method, b.method);
    EXPECT_EQ(a.spp, b.spp);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.cache_key, b.cache_key);
  }

  fs::path dir_;
  sb::core::Scene scene_;
  ref::GBuffer g_;
};

TEST_F(referenceCache, SecondGetIsFromCacheAndIdentical) {
  const ref::Result a = get();
  EXPECT_FALSE(a.from_cache);
  EXPECT_GT(a.seconds, 0.0);
  EXPECT_EQ(a.cache_key.size(), 16u);
  EXPECT_TRUE(fs::exists(file(a.cache_key)));
  const ref::Result b = get();
  EXPECT_TRUE(b.from_cache);
  EXPECT_EQ(b.seconds, 0.0);
  expect_same(a, b);
  // compute() agrees with what was cached.
  ref::Result c = ref::compute(scene_, g_.positions, g_.normals, {16, 1});
  c.cache_key = a.cache_key;
  expect_same(a, c);
  // No temp files left behind: the reference, and its key's lock file
  // (empty; it stays, reference.h says why).
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    ++files;
    if (e.path().extension() == ".lock") {
      EXPECT_EQ(e.path().stem(), a.cache_key);
      EXPECT_EQ(fs::file_size(e.path()), 0u);
    } else {
      EXPECT_EQ(e.path().extension(), ".sbref");
    }
  }
  EXPECT_EQ(files, 2);
}

TEST_F(referenceCache, KeyFollowsEverythingVisibilityDependsOn) {
  const std::string k = key(scene_);
  EXPECT_EQ(k, key(scene_));
  EXPECT_NE(k, key(scene_, {32, 1}));
  EXPECT_NE(k, key(scene_, {16, 2}));
  sb::core::Scene s = scene_;
  s.light.center.x += 0.01f;
  EXPECT_NE(k, key(s));
  s = scene_;
  s.light.half_v *= 1.5f;
  EXPECT_NE(k, key(s));
  s = scene_;
  s.meshes[1].positions[5].y += 1e-3f;  // a caster vertex
  EXPECT_NE(k, key(s));
  s = scene_;
  s.light.intensity = 5.0f;  // brightness does not change visibility
  EXPECT_EQ(k, key(s));

  ref::GBuffer g = g_;
  auto* bytes = reinterpret_cast<unsigned char*>(g.positions.data.data());
  bytes[1000] ^= 1;  // one bit of one position
  EXPECT_NE(k, ref::cache_key(scene_, g.positions, g.normals, {16, 1}));
  g = g_;
  g.normals.data[77] += 1e-3f;
  EXPECT_NE(k, ref::cache_key(scene_, g.positions, g.normals, {16, 1}));
}

TEST_F(referenceCache, DamagedFilesAreIgnoredAndReplaced) {
  const ref::Result a = get();
  const fs::path f = file(a.cache_key);
  const auto size = fs::file_size(f);

  fs::resize_file(f, size / 2);  // truncated
  ref::Result b = get();
  EXPECT_FALSE(b.from_cache);
  expect_same(a, b);
  EXPECT_EQ(fs::file_size(f), size);  // rewritten whole
  EXPECT_TRUE(get().from_cache);

  {  // one flipped byte in the middle of the planes
    std::fstream io(f, std::ios::in | std::ios::out | std::ios::binary);
    io.seekp(std::streamoff(size - 100));
    io.put('\x7f');
  }
  b = get();
  EXPECT_FALSE(b.from_cache);
  expect_same(a, b);

  {  // not a cache file at all
    std::ofstream out(f, std::ios::binary | std::ios::trunc);
    out << "hello";
  }
  EXPECT_FALSE(get().from_cache);

  // A valid file for other settings, stored under this key's name.
  const ref::Result other = get({16, 2});
  fs::copy_file(file(other.cache_key), f, fs::copy_options::overwrite_existing);
  b = get();
  EXPECT_FALSE(b.from_cache);
  expect_same(a, b);
}

// Sets (or, with nullptr, unsets) an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      old_ = old;
      had_ = true;
    }
    if (value != nullptr)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_, old_.c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

TEST_F(referenceCache, EnvironmentPinsTheIsaWhenTheSettingsDoNot) {
  const std::string sse2 = key(scene_, {16, 1, "isa=sse2"});
  {
    ScopedEnv config("SHADOWBENCH_EMBREE_CONFIG", nullptr);
    ScopedEnv isa("SHADOWBENCH_EMBREE_ISA", "sse2");  // the older name; every x86-64 has it
    EXPECT_EQ(sse2, key(scene_));
    EXPECT_EQ(ref::compute(scene_, g_.positions, g_.normals, {16, 1}).isa, "sse2");
  }
  {
    ScopedEnv config("SHADOWBENCH_EMBREE_CONFIG", "max_isa=sse2");
    EXPECT_EQ(sse2, key(scene_));
    // The settings win over the environment.
    if (ref::cpu_supports_isa("avx")) {
      EXPECT_NE(sse2, key(scene_, {16, 1, "isa=avx"}));
    }
  }
  {
    ScopedEnv config("SHADOWBENCH_EMBREE_CONFIG", "isa=avx-9000");
    EXPECT_THROW(ref::compute(scene_, g_.positions, g_.normals, {16, 1}), std::invalid_argument);
  }
  if (ref::best_cpu_isa() != "sse2") {
    ScopedEnv config("SHADOWBENCH_EMBREE_CONFIG", nullptr);
    ScopedEnv isa("SHADOWBENCH_EMBREE_ISA", nullptr);
    EXPECT_NE(sse2, key(scene_));
  }
}

TEST_F(referenceCache, UnwritableDirectoryIsAJobError) {
  fs::create_directories(dir_);
  const fs::path blocker = dir_ / "not_a_dir";
  std::ofstream(blocker) << "x";
  EXPECT_THROW(ref::get(scene_, g_.positions, g_.normals, {16, 1}, (blocker / "cache").string()),
               sb::core::JobError);
}

}  // namespace
