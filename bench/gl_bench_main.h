#pragma once
// main() of the benchmarks that drive GL: one OSMesa context for the
// process, made before the benchmarks run and destroyed after them, once
// `release` has dropped the benchmarks' own GL objects.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>
#include <functional>
#include <memory>

#include "gl/context.h"

inline int run_gl_benchmarks(int argc, char** argv, const char* program,
                             const std::function<void()>& release = {}) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::unique_ptr<sb::gl::Context> context;
  try {
    context = sb::gl::create_context(sb::gl::Backend::OSMesa);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: no GL context: %s\n", program, e.what());
    return 3;
  }
  benchmark::AddCustomContext("gl_renderer", context->renderer());
  benchmark::RunSpecifiedBenchmarks();
  if (release) release();
  context.reset();
  benchmark::Shutdown();
  return 0;
}
