#pragma once
// Helpers shared by the metrics tests.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "core/image.h"

namespace sb::test {

// A fresh directory removed again at scope end.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = std::filesystem::temp_directory_path() /
            ("sb_metrics_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Uniform noise in [lo, hi), reproducible on every standard library (the
// std distributions are not).
inline core::ImageF noise_image(int w, int h, int c, uint32_t seed, float lo = 0.0f,
                                float hi = 1.0f) {
  std::mt19937 rng(seed);
  core::ImageF img(w, h, c);
  for (float& v : img.data) {
    v = lo + (hi - lo) * static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f);
  }
  return img;
}

// A smooth pattern with edges, so SSIM sees structure rather than noise.
inline core::ImageF pattern_image(int w, int h, int c) {
  core::ImageF img(w, h, c);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int ch = 0; ch < c; ++ch) {
        const double s = 0.5 + 0.3 * std::sin(0.21 * x + 0.7 * ch) * std::cos(0.17 * y);
        const double edge = (x + 2 * y + 5 * ch) % 29 < 11 ? 0.15 : 0.0;
        img.at(x, y, ch) = static_cast<float>(s + edge);
      }
    }
  }
  return img;
}

// 3x3 box blur (clamped borders) followed by a shift of (dx, dy) pixels.
inline core::ImageF blur_shift(const core::ImageF& src, int dx, int dy) {
  core::ImageF out(src.width, src.height, src.channels);
  auto clampi = [](int v, int n) { return v < 0 ? 0 : (v >= n ? n - 1 : v); };
  for (int y = 0; y < src.height; ++y) {
    for (int x = 0; x < src.width; ++x) {
      for (int c = 0; c < src.channels; ++c) {
        float sum = 0;
        for (int j = -1; j <= 1; ++j) {
          for (int i = -1; i <= 1; ++i) {
            sum += src.at(clampi(x - dx + i, src.width), clampi(y - dy + j, src.height), c);
          }
        }
        out.at(x, y, c) = sum / 9.0f;
      }
    }
  }
  return out;
}

// Raw dump read by ssim_oracle.py: "SBF1", uint32 w, h, c, float32 data
// (this test only runs on little-endian hosts).
inline void write_dump(const std::string& path, const core::ImageF& img) {
  std::ofstream f(path, std::ios::binary);
  const uint32_t head[3] = {static_cast<uint32_t>(img.width), static_cast<uint32_t>(img.height),
                            static_cast<uint32_t>(img.channels)};
  f.write("SBF1", 4);
  f.write(reinterpret_cast<const char*>(head), sizeof head);
  f.write(reinterpret_cast<const char*>(img.data.data()),
          static_cast<std::streamsize>(img.data.size() * sizeof(float)));
  if (!f) throw std::runtime_error("cannot write " + path);
}

inline core::ImageF read_dump(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char magic[4];
  uint32_t head[3];
  f.read(magic, 4);
  f.read(reinterpret_cast<char*>(head), sizeof head);
  if (!f || std::string(magic, 4) != "SBF1") throw std::runtime_error("bad dump " + path);
  core::ImageF img(static_cast<int>(head[0]), static_cast<int>(head[1]), static_cast<int>(head[2]));
  f.read(reinterpret_cast<char*>(img.data.data()),
         static_cast<std::streamsize>(img.data.size() * sizeof(float)));
  if (!f) throw std::runtime_error("short dump " + path);
  return img;
}

}  // namespace sb::test
