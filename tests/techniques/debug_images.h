#pragma once
// A test's V as a binary PGM (0..1 → 0..255) in the folder an environment
// variable names, for looking at what a GL test rendered: nothing when the
// variable is unset. `bottom_up`: row 0 is GL's bottom row, written last.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/image.h"

namespace sb::test {

inline void write_pgm_if_asked(const core::ImageF& img, const char* env, const std::string& name,
                               bool bottom_up = false) {
  const char* dir = std::getenv(env);
  if (dir == nullptr) return;
  std::ofstream f(std::string(dir) + "/" + name + ".pgm", std::ios::binary);
  f << "P5\n" << img.width << " " << img.height << "\n255\n";
  for (int row = 0; row < img.height; ++row) {
    const int y = bottom_up ? img.height - 1 - row : row;
    for (int x = 0; x < img.width; ++x)
      f.put(char(std::clamp(int(std::lround(255.0f * img.at(x, y))), 0, 255)));
  }
}

}  // namespace sb::test
