#pragma once
// The most triangles a scene generator may make, checked from its parameters
// before anything is built (SceneType::check): the legal maxima of every
// parameter together would ask for terabytes. 2^24 triangles is 4× the
// largest sweep in configs/ and fits the reference's BVH in about 2 GB.
#include <cstdint>
#include <string>
#include <utility>

namespace sb {

constexpr uint64_t kMaxGeneratedTriangles = uint64_t(1) << 24;

// {param, problem} for SceneType::check when `estimate` is over the budget,
// else {"", ""}. `param` is the parameter to blame (the main count).
inline std::pair<std::string, std::string> triangle_budget(uint64_t estimate,
                                                           const std::string& param) {
  if (estimate <= kMaxGeneratedTriangles) return {"", ""};
  return {param, "these parameters make about " + std::to_string(estimate) +
                     " triangles, over the generators' limit of " +
                     std::to_string(kMaxGeneratedTriangles) + "; use a glTF file for more"};
}

// a*b saturating at UINT64_MAX.
inline uint64_t budget_mul(uint64_t a, uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

}  // namespace sb
