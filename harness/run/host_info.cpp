#include "run/host_info.h"

#include <sched.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>
#include <vector>

#include "run/code_identity.h"

// CMake passes these to this file only (harness/run/CMakeLists.txt).
#ifndef SHADOWBENCH_COMPILER
#define SHADOWBENCH_COMPILER ""
#endif
#ifndef SHADOWBENCH_BUILD_TYPE
#define SHADOWBENCH_BUILD_TYPE ""
#endif
#ifndef SHADOWBENCH_CXX_FLAGS
#define SHADOWBENCH_CXX_FLAGS ""
#endif

namespace sb::run {

using record::build_fingerprint;
using record::BuildRecord;
using record::CpuRecord;
using record::host_fingerprint;
using record::HostRecord;
using record::kCpuIsaFeatures;
using record::kTimingEnvironment;
using record::parse_gl_stack;

namespace {

std::string_view trimmed(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

// The text of a small file (procfs and sysfs report no size); nullopt when
// it cannot be opened.
std::optional<std::string> file_text(const char* path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The value of the first line `key<sep>value` of `text`.
std::optional<std::string> line_value(std::string_view text, std::string_view key, char sep) {
  while (!text.empty()) {
    const size_t eol = text.find('\n');
    const std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
    const size_t at = line.find(sep);
    if (at != std::string_view::npos && trimmed(line.substr(0, at)) == key)
      return std::string(trimmed(line.substr(at + 1)));
  }
  return std::nullopt;
}

std::vector<std::string> cpu_isa() {
  std::vector<std::string> out;
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  // __builtin_cpu_supports takes literals only: one per kCpuIsaFeatures entry.
  const bool has[] = {
      __builtin_cpu_supports("sse4.2") != 0,   __builtin_cpu_supports("avx") != 0,
      __builtin_cpu_supports("avx2") != 0,     __builtin_cpu_supports("fma") != 0,
      __builtin_cpu_supports("avx512f") != 0,  __builtin_cpu_supports("avx512bw") != 0,
      __builtin_cpu_supports("avx512dq") != 0, __builtin_cpu_supports("avx512vl") != 0};
  static_assert(std::size(has) == std::size(kCpuIsaFeatures));
  for (size_t i = 0; i < std::size(has); ++i)
    if (has[i]) out.emplace_back(kCpuIsaFeatures[i]);
#endif
  return out;
}

// What does not change while the process runs, read once.
HostRecord machine() {
  HostRecord h;
  h.hardware_threads = std::thread::hardware_concurrency();
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) == 0) h.name = name;
  CpuRecord cpu;
  if (const auto text = file_text("/proc/cpuinfo"))
    cpu.model = cpuinfo_model_name(*text).value_or("");
  cpu.isa = cpu_isa();
  cpu.logical_cores = usable_cpus();
  h.cpu = std::move(cpu);
  if (const auto text = file_text("/etc/os-release")) h.os = os_release_pretty_name(*text);
  utsname u{};
  if (uname(&u) == 0) h.kernel = u.release;
  if (const auto governor = file_text("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor"))
    h.cpu_governor = std::string(trimmed(*governor));
  return h;
}

}  // namespace

std::optional<std::string> cpuinfo_model_name(std::string_view cpuinfo) {
  auto model = line_value(cpuinfo, "model name", ':');
  if (model && model->empty()) return std::nullopt;
  return model;
}

std::optional<std::string> os_release_pretty_name(std::string_view os_release) {
  auto name = line_value(os_release, "PRETTY_NAME", '=');
  if (!name) return std::nullopt;
  if (name->size() >= 2 && (name->front() == '"' || name->front() == '\'') &&
      name->back() == name->front())
    *name = name->substr(1, name->size() - 2);
  return name;
}

HostRecord describe_host(const std::string& gl_renderer, const std::string& gl_version,
                         const std::string& embree_isa) {
  static const HostRecord kMachine = machine();
  HostRecord h = kMachine;
  for (const char* name : kTimingEnvironment)
    if (const char* value = std::getenv(name)) h.env[name] = value;
  // llvmpipe's rasteriser threads (read at context creation; default: cores).
  if (const char* lp = std::getenv("LP_NUM_THREADS")) h.lp_num_threads = lp;
  h.gl_stack = parse_gl_stack(gl_renderer, gl_version);
  if (!embree_isa.empty()) h.embree_isa = embree_isa;
  h.fingerprint = host_fingerprint(h, gl_renderer, gl_version);
  return h;
}

BuildRecord describe_build() {
  BuildRecord b;
  b.version = SHADOWBENCH_VERSION;
  b.compiler = SHADOWBENCH_COMPILER;
  b.build_type = SHADOWBENCH_BUILD_TYPE;
  b.cxx_flags = std::string(trimmed(SHADOWBENCH_CXX_FLAGS));
  b.fingerprint = build_fingerprint(b);
  const CodeIdentity& code = this_code();
  const auto present = [](const std::string& s) {
    return s.empty() ? std::nullopt : std::optional(s);
  };
  b.driver_sha256 = present(code.driver_sha256);
  b.core_sha256 = present(code.core_sha256);
  b.plugin_api_sha256 = present(code.plugin_api_sha256);
  return b;
}

std::int64_t usable_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
  return std::thread::hardware_concurrency();
}

std::optional<double> one_minute_load_average() {
  double load[1] = {0};
  if (getloadavg(load, 1) != 1) return std::nullopt;
  return load[0];
}

}  // namespace sb::run
