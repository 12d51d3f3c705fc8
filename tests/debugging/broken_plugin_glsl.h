#pragma once
// What tests/debugging/broken_plugin.cpp fails with, shared with the test
// that checks the messages.
namespace broken {

// Line 1 is the empty line after R"(; the typo, "flaot", is on line 4.
inline constexpr int kTypoLine = 4;
inline constexpr const char* kTypoGlsl = R"(
float lit_fraction(vec3 t) {
  float lit = shadow_tap(t, vec2(0.0));
  flaot half_lit = lit * 0.5;
  return half_lit;
}
)";

// A semantic error (a name nothing declares) on line 5, in a lit_fraction
// that calls a kit piece passed as kit GLSL before it.
inline constexpr int kUndefinedLine = 5;
inline constexpr const char* kUndefinedGlsl = R"(
float lit_fraction(vec3 t) {
  float lit = pcf_grid(t, 1, 1.0 / vec2(textureSize(shadow_map, 0)));
  float half_lit = lit * 0.5;
  return rotaton_by_turns(half_lit);
}
)";

inline constexpr const char* kLinesMessage =
    "first line of the failure\nsecond line | with a bar\n\n  third line, indented\n";

}  // namespace broken
