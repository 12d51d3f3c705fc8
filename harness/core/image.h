#pragma once
// A float image in row-major order, row 0 at the top (as in image files).
#include <cstddef>
#include <vector>

namespace sb::core {

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<float> data;

  ImageF() = default;
  ImageF(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, fill) {}

  size_t pixel_count() const { return static_cast<size_t>(width) * height; }
  size_t index(int x, int y, int c = 0) const {
    return (static_cast<size_t>(y) * width + x) * channels + c;
  }
  float& at(int x, int y, int c = 0) { return data[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return data[index(x, y, c)]; }
  bool same_shape(const ImageF& o) const {
    return width == o.width && height == o.height && channels == o.channels;
  }
};

}  // namespace sb::core
