#pragma once
// What `run` writes into every record's "host" and "build": this machine
// (CPU, ISA, cores, OS, llvmpipe's environment knobs, the GL stack) and this
// build (compiler, build type, flags), each with its fingerprint
// (record/host_record.h; docs/results.md, "host and build").
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "record/host_record.h"

namespace sb::run {

// This machine, as it times a job with a context that reports `gl_renderer`
// and `gl_version`; `embree_isa` is the reference's ("" when unknown).
// Reads /proc/cpuinfo, /etc/os-release and sysfs once per process.
record::HostRecord describe_host(const std::string& gl_renderer, const std::string& gl_version,
                                 const std::string& embree_isa);

// CPUs this process may run on (a container's cpuset, taskset), which is
// what llvmpipe sizes its threads by; the online count when unknown.
std::int64_t usable_cpus();

// The 1-minute load average (/proc/loadavg, through getloadavg); nullopt
// where the system does not say.
std::optional<double> one_minute_load_average();

// This build: SHADOWBENCH_VERSION and what CMake passed to host_info.cpp.
record::BuildRecord describe_build();

// The parsers describe_host uses, for tests: the first "model name" of a
// /proc/cpuinfo text, and PRETTY_NAME of an os-release text (quotes removed).
std::optional<std::string> cpuinfo_model_name(std::string_view cpuinfo);
std::optional<std::string> os_release_pretty_name(std::string_view os_release);

}  // namespace sb::run
