#pragma once
// The one-tailed Chebyshev bound shared by VSM and EVSM.
namespace sb::techniques::filtered_map {

// `chebyshev_upper_bound(m, t, min_variance, bleeding_reduction)`: the most
// light a receiver at depth t can see given the filtered first two moments
// m of the occluder depth (Donnelly & Lauritzen 2006), with the variance
// floored at min_variance and light-bleeding reduction (Lauritzen 2007):
// bounds below `bleeding_reduction` become 0, the rest are rescaled to [0,1].
inline constexpr const char* kChebyshevGlsl = R"(
float chebyshev_upper_bound(vec2 m, float t, float min_variance, float bleeding_reduction) {
  if (t <= m.x) return 1.0;
  float variance = max(m.y - m.x * m.x, min_variance);
  float d = t - m.x;
  float p = variance / (variance + d * d);
  return clamp_unit((p - bleeding_reduction) / (1.0 - bleeding_reduction));
}
)";

}  // namespace sb::techniques::filtered_map
