#pragma once
// The vector widths the metrics' hot loops are compiled for, picked at run
// time for the CPU at hand (ssim_kernels.h, flip.cpp): the build targets
// baseline x86-64, so without this they would run SSE2-wide everywhere.
#include <string>

namespace sb::metrics::detail {

enum class SimdPath { Baseline, Avx2, Avx512 };

std::string to_string(SimdPath path);
// Whether this CPU can run the path (Baseline: always; the others only on
// x86-64, where they are built). Asking a kernel for a path that does not
// run here is the caller's error.
bool runs_here(SimdPath path);
// The widest path this CPU runs: what the metrics use.
SimdPath widest_simd_path();

}  // namespace sb::metrics::detail
