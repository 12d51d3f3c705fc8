#pragma once
// record["host"] and record["build"]: the machine and the build that timed a
// job, and their fingerprints (docs/results.md, "host and build").
//
// Two runs' absolute frame times compare only when their host fingerprints
// are equal: the fingerprint hashes what changes llvmpipe's speed (the CPU,
// its ISA, the cores, the GL stack, llvmpipe's environment knobs, the OS)
// and nothing that does not (the host name, the kernel's patch level, the
// time). The members a build before host fingerprints did not write are
// optional: such records still read, and have no fingerprint.
// run/host_info.h gathers all of it; this file only holds and hashes it.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// host.cpu
struct CpuRecord {
  static constexpr RecordDoc kSchema{"CpuRecord", "the CPU"};

  std::string model;               // /proc/cpuinfo "model name"; "" when unknown
  std::vector<std::string> isa;    // of kCpuIsaFeatures, those the CPU has, in that order
  std::int64_t logical_cores = 0;  // CPUs this process may run on

  template <class V>
  static void describe(V& v) {
    v.field("model", &CpuRecord::model,
            {"",
             "`/proc/cpuinfo` \"model name\"; `\"\"` where there is none, as on most ARM "
             "kernels"});
    v.field("isa", &CpuRecord::isa,
            {"",
             "those of `sse4.2`, `avx`, `avx2`, `fma`, `avx512f`, `avx512bw`, `avx512dq`, "
             "`avx512vl` that the CPU and OS support; empty off x86"});
    v.field("logical_cores", &CpuRecord::logical_cores,
            {"",
             "the CPUs this process may run on: its affinity mask, which a container's "
             "cpuset or `taskset` narrows"});
  }
};

// The ISA features a CPU record names (x86; none elsewhere).
inline constexpr const char* kCpuIsaFeatures[] = {"sse4.2",  "avx",      "avx2",     "fma",
                                                  "avx512f", "avx512bw", "avx512dq", "avx512vl"};

// Environment variables that change llvmpipe's speed: host.env holds the set ones.
inline constexpr const char* kTimingEnvironment[] = {"LP_NUM_THREADS", "LP_NATIVE_VECTOR_WIDTH",
                                                     "GALLIUM_DRIVER", "LP_PERF"};

// host.gl_stack: what the GL strings say about the rendering stack. Each is
// absent when the strings do not say it (a GPU driver has no vector width).
struct GlStack {
  static constexpr RecordDoc kSchema{
      "GlStack",
      "what the GL strings say about the rendering stack; each member absent when they do not "
      "say it (a GPU driver's)"};

  std::optional<std::string> mesa_version;  // "22.3.6", from gl_version's "Mesa 22.3.6"
  std::optional<std::string> llvm_version;  // "15.0.6", from gl_renderer's "LLVM 15.0.6"
  std::optional<int> vector_bits;           // 256, from llvmpipe's "(LLVM 15.0.6, 256 bits)"

  template <class V>
  static void describe(V& v) {
    v.field("mesa_version", &GlStack::mesa_version,
            {"", "`22.3.6` from `gl_version` \"4.5 (Core Profile) Mesa 22.3.6\""});
    v.field("llvm_version", &GlStack::llvm_version,
            {"", "`15.0.6` from `gl_renderer` \"llvmpipe (LLVM 15.0.6, 256 bits)\""});
    v.field("vector_bits", &GlStack::vector_bits, {"bits", "llvmpipe's vector width"});
  }

  bool operator==(const GlStack&) const = default;
};

// Parses gl_renderer ("llvmpipe (LLVM 15.0.6, 256 bits)") and gl_version
// ("4.5 (Core Profile) Mesa 22.3.6"); never throws.
GlStack parse_gl_stack(const std::string& gl_renderer, const std::string& gl_version);

struct HostRecord {
  static constexpr RecordDoc kSchema{
      "HostRecord",
      "the machine that timed the job (\"`host` and its fingerprint\" below); the members "
      "below `name` are absent from records older than the fingerprint"};

  std::int64_t hardware_threads = 0;
  std::optional<std::string> lp_num_threads;  // LP_NUM_THREADS, when set
  std::optional<std::string> name;
  // The fingerprint's members: written by every build since they exist,
  // absent in older records (then fingerprint is absent too).
  std::optional<CpuRecord> cpu;
  std::optional<GlStack> gl_stack;
  std::map<std::string, std::string> env;   // the kTimingEnvironment variables that are set
  std::optional<std::string> os;            // /etc/os-release PRETTY_NAME
  std::optional<std::string> kernel;        // uname release
  std::optional<std::string> cpu_governor;  // cpu0's cpufreq scaling_governor, when there is one
  std::optional<std::string> embree_isa;    // the reference's Embree ISA, when known
  std::optional<std::string> fingerprint;   // host_fingerprint(): 16 hex digits

  template <class V>
  static void describe(V& v) {
    using H = HostRecord;
    v.field("hardware_threads", &H::hardware_threads, {"", "std::thread::hardware_concurrency"});
    v.field("lp_num_threads", &H::lp_num_threads, {"", "`LP_NUM_THREADS`, when set"});
    v.field("name", &H::name, {"", "the host name"});
    v.field("cpu", &H::cpu, {"", "the CPU"});
    v.field("gl_stack", &H::gl_stack, {"", "what the GL strings say"});
    v.field("env", &H::env,
            {"",
             "the set ones of `LP_NUM_THREADS`, `LP_NATIVE_VECTOR_WIDTH`, `GALLIUM_DRIVER`, "
             "`LP_PERF` (name → value; `{}` when none is)",
             Presence::OlderLack});
    v.field("os", &H::os, {"", "`/etc/os-release` `PRETTY_NAME`"});
    v.field("kernel", &H::kernel, {"", "`uname -r`"});
    v.field("cpu_governor", &H::cpu_governor,
            {"",
             "`/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor`, when the machine has "
             "one (VMs often do not)"});
    v.field("embree_isa", &H::embree_isa,
            {"", "the Embree ISA the run's references use (also `reference.embree_isa`)"});
    v.field("fingerprint", &H::fingerprint, {"", "16 hex digits (below)"});
  }

  nlohmann::json to_json() const;
  static HostRecord from_json(const Fields& f);
};

// record["build"]
struct BuildRecord {
  static constexpr RecordDoc kSchema{"BuildRecord", "the build that ran the job"};

  std::string version;
  std::optional<std::string> compiler;     // "GNU 12.2.0"
  std::optional<std::string> build_type;   // "Release"
  std::optional<std::string> cxx_flags;    // CMAKE_CXX_FLAGS and those of the build type
  std::optional<std::string> fingerprint;  // build_fingerprint(): 16 hex digits
  // SHA-256 of the code that ran: the driver executable and the harness's
  // two libraries (shadowbench_core, shadowbench_plugin_api). Not part of
  // the fingerprint, which names the toolchain; the job's spec holds them,
  // so that a rebuilt harness reruns. Absent in older records.
  std::optional<std::string> driver_sha256, core_sha256, plugin_api_sha256;

  template <class V>
  static void describe(V& v) {
    using B = BuildRecord;
    v.field("version", &B::version, {"", "shadowbench's version"});
    v.field("compiler", &B::compiler, {"", "CMake's compiler id and version, `GNU 12.2.0`"});
    v.field("build_type", &B::build_type, {"", "`Release`"});
    v.field("cxx_flags", &B::cxx_flags, {"", "`CMAKE_CXX_FLAGS` and those of the build type"});
    v.field("fingerprint", &B::fingerprint,
            {"",
             "16 hex digits over those four: `compare` shows a different one and never "
             "refuses it"});
    v.field("driver_sha256", &B::driver_sha256,
            {"", "SHA-256 of the driver executable (`/proc/self/exe`); not in the fingerprint"});
    v.field("core_sha256", &B::core_sha256,
            {"", "SHA-256 of `shadowbench_core` as loaded; in the spec"});
    v.field("plugin_api_sha256", &B::plugin_api_sha256,
            {"", "SHA-256 of `shadowbench_plugin_api` as loaded; in the spec"});
  }

  nlohmann::json to_json() const;
  static BuildRecord from_json(const Fields& f);
};

// What the host fingerprint hashes, as (name, value) in a fixed order:
// cpu.model, cpu.isa (space-separated), cpu.logical_cores, gl_renderer,
// gl_version, env.<each kTimingEnvironment variable> ("" when unset), os.
// A member the record lacks has the value "".
std::vector<std::pair<std::string, std::string>> host_fingerprint_fields(
    const HostRecord& host, const std::string& gl_renderer, const std::string& gl_version);
// 16 hex digits of a Hasher over host_fingerprint_fields (names and values).
std::string host_fingerprint(const HostRecord& host, const std::string& gl_renderer,
                             const std::string& gl_version);

// What the build fingerprint hashes: version, compiler, build_type, cxx_flags.
std::vector<std::pair<std::string, std::string>> build_fingerprint_fields(const BuildRecord& b);
std::string build_fingerprint(const BuildRecord& b);

// The fields of two field lists whose values differ, as
// `cpu.model: "AMD EPYC 7B13" vs "Intel Xeon Platinum 8481C"` (an empty
// value, unset or unknown, as `(none)`).
std::vector<std::string> field_differences(
    const std::vector<std::pair<std::string, std::string>>& a,
    const std::vector<std::pair<std::string, std::string>>& b);

}  // namespace sb::record
