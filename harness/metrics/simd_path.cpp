#include "metrics/simd_path.h"

namespace sb::metrics::detail {

std::string to_string(SimdPath path) {
  switch (path) {
    case SimdPath::Avx2:
      return "avx2";
    case SimdPath::Avx512:
      return "avx512";
    case SimdPath::Baseline:
      break;
  }
  return "baseline";
}

bool runs_here(SimdPath path) {
  switch (path) {
#if defined(__x86_64__)
    case SimdPath::Avx2:
      return __builtin_cpu_supports("avx2");
    case SimdPath::Avx512:
      return __builtin_cpu_supports("avx512f");
#else
    case SimdPath::Avx2:
    case SimdPath::Avx512:
      return false;
#endif
    case SimdPath::Baseline:
      break;
  }
  return true;
}

SimdPath widest_simd_path() {
  static const SimdPath widest = runs_here(SimdPath::Avx512) ? SimdPath::Avx512
                                 : runs_here(SimdPath::Avx2) ? SimdPath::Avx2
                                                             : SimdPath::Baseline;
  return widest;
}

}  // namespace sb::metrics::detail
