#pragma once
// Which of Embree's instruction sets the reference runs on.
//
// Embree picks its kernels at run time, and the kernels differ: the AVX-512
// ones trace 16-wide packets natively, the AVX/AVX2 ones 8-wide, the SSE ones
// 4-wide, and results can differ in single rays at silhouettes. So the ISA is
// a setting of the reference (part of its cache key and its record), chosen
// with Embree's own device-config syntax:
//   ""                  the best ISA this CPU has
//   "isa=avx2"          exactly that ISA (an error if the CPU lacks it)
//   "max_isa=avx2"      the best ISA this CPU has, but at most avx2
// ISA names: sse2, sse4.2, avx, avx2, avx512.
#include <stdexcept>
#include <string>
#include <vector>

namespace sb::reference {

// Embree's x86 ISAs, lowest first.
const std::vector<std::string>& embree_isas();

// The best ISA this CPU runs (with every extension Embree's kernels use).
std::string best_cpu_isa();
bool cpu_supports_isa(const std::string& isa);

// A device config that cannot be run on this machine (its CPU lacks the ISA).
class UnsupportedIsa : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws std::invalid_argument naming the bad token when `config` is not of
// the forms above (Embree itself would silently ignore an unknown name).
void check_embree_config(const std::string& config);

// The ISA Embree will run for `config` on this CPU. Throws
// std::invalid_argument for a malformed config, UnsupportedIsa when the CPU
// lacks the ISA that "isa=" asks for (Embree would run kernels the CPU
// cannot execute).
std::string resolve_isa(const std::string& config);

// The config used when neither the experiment nor the command line sets one:
// SHADOWBENCH_EMBREE_CONFIG, else "isa=$SHADOWBENCH_EMBREE_ISA" (older name),
// else "". Lets a whole test suite run on one ISA (e.g. isa=avx2 on an
// AVX-512 machine, to take the path AVX2-only CPUs take).
std::string default_embree_config();

}  // namespace sb::reference
