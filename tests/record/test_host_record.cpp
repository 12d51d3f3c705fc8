// record["host"] and record["build"]: the GL strings parsed into the
// rendering stack (llvmpipe, GPU drivers, garbage); the host fingerprint
// stable for equal inputs and changed by exactly the timing-relevant
// fields; round trips; a record from before the fingerprint still reads;
// and what run/host_info.h gathers on this machine. No GL.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <functional>
#include <set>

#include "record/host_record.h"
#include "record/job_record.h"
#include "run/host_info.h"
#include "sample_records.h"

namespace sb {

using record::build_fingerprint;
using record::BuildRecord;
using record::CpuRecord;
using record::field_differences;
using record::GlStack;
using record::host_fingerprint;
using record::host_fingerprint_fields;
using record::HostRecord;
using record::JobRecord;
using record::kCpuIsaFeatures;
using record::parse_gl_stack;
using record::RecordError;
using run::cpuinfo_model_name;
using run::describe_build;
using run::describe_host;
using run::os_release_pretty_name;

namespace {

using json = nlohmann::json;

TEST(HostRecord, ParsesLlvmpipeStrings) {
  const GlStack s =
      parse_gl_stack("llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6");
  EXPECT_EQ(s.mesa_version, "22.3.6");
  EXPECT_EQ(s.llvm_version, "15.0.6");
  EXPECT_EQ(s.vector_bits, 256);
  const GlStack wide = parse_gl_stack("llvmpipe (LLVM 17.0.6, 512 bits)",
                                      "4.5 (Compatibility Profile) Mesa 24.1.0-devel (git-3a1b2c)");
  EXPECT_EQ(wide.mesa_version, "24.1.0-devel");
  EXPECT_EQ(wide.llvm_version, "17.0.6");
  EXPECT_EQ(wide.vector_bits, 512);
}

TEST(HostRecord, GpuStringsHaveNoVectorWidth) {
  // NVIDIA's own driver: no Mesa, no LLVM.
  EXPECT_EQ(parse_gl_stack("NVIDIA GeForce RTX 3080/PCIe/SSE2", "4.6.0 NVIDIA 535.104.05"),
            GlStack{});
  // radeonsi compiles shaders with LLVM: Mesa and LLVM, but no vector width.
  const GlStack amd = parse_gl_stack("AMD Radeon RX 6800 (navi21, LLVM 15.0.7, DRM 3.49, 6.1.0)",
                                     "4.6 (Core Profile) Mesa 23.1.0");
  EXPECT_EQ(amd.mesa_version, "23.1.0");
  EXPECT_EQ(amd.llvm_version, "15.0.7");
  EXPECT_FALSE(amd.vector_bits.has_value());
}

TEST(HostRecord, GarbageGlStringsParseToNothing) {
  const char* garbage[] = {"",
                           "LLVM",
                           "Mesa",
                           "Mesa ",
                           "XMesa 1.0",
                           "llvmpipe (LLVM , bits)",
                           "llvmpipe ( bits)",
                           "llvmpipe (LLVM x, 99999999 bits)",
                           "\xff\xfe Mesa\xff",
                           "llvmpipe"};
  for (const char* g : garbage) {
    const GlStack s = parse_gl_stack(g, g);
    EXPECT_FALSE(s.mesa_version.has_value()) << g;
    EXPECT_FALSE(s.llvm_version.has_value()) << g;
    EXPECT_FALSE(s.vector_bits.has_value()) << g;
  }
  // "(test)" as the synthetic records have it.
  EXPECT_EQ(parse_gl_stack("llvmpipe (test)", "4.5 (Core Profile) Mesa"), GlStack{});
}

HostRecord sample_host() {
  HostRecord h;
  h.hardware_threads = 2;
  h.name = "ci-runner-1";
  h.cpu = CpuRecord{"AMD EPYC 7B13", {"sse4.2", "avx", "avx2", "fma"}, 2};
  h.gl_stack = parse_gl_stack("llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6");
  h.env = {{"LP_NUM_THREADS", "2"}};
  h.lp_num_threads = "2";
  h.os = "Debian GNU/Linux 12 (bookworm)";
  h.kernel = "6.1.0-27-cloud-amd64";
  h.cpu_governor = "performance";
  h.embree_isa = "avx2";
  return h;
}

constexpr const char* kRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
constexpr const char* kVersion = "4.5 (Core Profile) Mesa 22.3.6";

TEST(HostRecord, FingerprintIsStableAndIgnoresTheHostName) {
  const HostRecord a = sample_host();
  const std::string fp = host_fingerprint(a, kRenderer, kVersion);
  EXPECT_EQ(fp.size(), 16u);
  EXPECT_EQ(fp.find_first_not_of("0123456789abcdef"), std::string::npos) << fp;
  EXPECT_EQ(host_fingerprint(sample_host(), kRenderer, kVersion), fp);
  // Nothing that leaves frame times alone changes it.
  const std::function<void(HostRecord&)> neutral[] = {
      [](HostRecord& h) { h.name = "ci-runner-2"; },
      [](HostRecord& h) { h.name.reset(); },
      [](HostRecord& h) { h.kernel = "6.1.0-28-cloud-amd64"; },
      [](HostRecord& h) { h.cpu_governor = "powersave"; },
      [](HostRecord& h) { h.embree_isa = "avx512"; },
      [](HostRecord& h) { h.hardware_threads = 64; },
      [](HostRecord& h) { h.fingerprint = "0000000000000000"; },
  };
  for (size_t i = 0; i < std::size(neutral); ++i) {
    HostRecord h = sample_host();
    neutral[i](h);
    EXPECT_EQ(host_fingerprint(h, kRenderer, kVersion), fp) << "change " << i;
  }
}

TEST(HostRecord, FingerprintChangesWithEveryTimingField) {
  const std::string fp = host_fingerprint(sample_host(), kRenderer, kVersion);
  const std::function<void(HostRecord&)> relevant[] = {
      [](HostRecord& h) { h.cpu->model = "Intel(R) Xeon(R) Platinum 8481C CPU @ 2.70GHz"; },
      [](HostRecord& h) { h.cpu->isa.push_back("avx512f"); },
      [](HostRecord& h) { h.cpu->logical_cores = 4; },
      [](HostRecord& h) { h.cpu.reset(); },
      [](HostRecord& h) { h.env.erase("LP_NUM_THREADS"); },
      [](HostRecord& h) { h.env["LP_NUM_THREADS"] = "1"; },
      [](HostRecord& h) { h.env["LP_NATIVE_VECTOR_WIDTH"] = "128"; },
      [](HostRecord& h) { h.env["GALLIUM_DRIVER"] = "softpipe"; },
      [](HostRecord& h) { h.env["LP_PERF"] = "no_mipmap"; },
      [](HostRecord& h) { h.os = "Ubuntu 24.04.1 LTS"; },
  };
  std::set<std::string> seen{fp};
  for (size_t i = 0; i < std::size(relevant); ++i) {
    HostRecord h = sample_host();
    relevant[i](h);
    const std::string other = host_fingerprint(h, kRenderer, kVersion);
    EXPECT_NE(other, fp) << "change " << i;
    seen.insert(other);
  }
  EXPECT_EQ(seen.size(), std::size(relevant) + 1);  // and no two changes collide
  EXPECT_NE(host_fingerprint(sample_host(), "llvmpipe (LLVM 15.0.6, 512 bits)", kVersion), fp);
  EXPECT_NE(host_fingerprint(sample_host(), kRenderer, "4.5 (Core Profile) Mesa 23.2.1"), fp);
}

TEST(HostRecord, DifferencesNameTheFields) {
  HostRecord other = sample_host();
  other.cpu->model = "Intel Xeon Platinum 8481C";
  other.name = "elsewhere";
  const auto d = field_differences(
      host_fingerprint_fields(sample_host(), kRenderer, kVersion),
      host_fingerprint_fields(other, "llvmpipe (LLVM 15.0.6, 512 bits)", kVersion));
  ASSERT_EQ(d.size(), 2u);
  // An unset knob reads as (none).
  HostRecord threads = sample_host();
  threads.env.erase("LP_NUM_THREADS");
  EXPECT_EQ(field_differences(host_fingerprint_fields(threads, kRenderer, kVersion),
                              host_fingerprint_fields(sample_host(), kRenderer, kVersion)),
            std::vector<std::string>{"env.LP_NUM_THREADS: (none) vs \"2\""});
  EXPECT_EQ(d[0], "cpu.model: \"AMD EPYC 7B13\" vs \"Intel Xeon Platinum 8481C\"");
  EXPECT_EQ(d[1],
            "gl_renderer: \"llvmpipe (LLVM 15.0.6, 256 bits)\" vs \"llvmpipe (LLVM 15.0.6, 512 "
            "bits)\"");
}

TEST(HostRecord, BuildFingerprintFollowsTheBuild) {
  BuildRecord b{"0.1.0",      "GNU 12.2.0", "Release",    "-O3 -DNDEBUG",
                std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  const std::string fp = build_fingerprint(b);
  EXPECT_EQ(fp.size(), 16u);
  EXPECT_EQ(build_fingerprint(b), fp);
  for (std::optional<std::string> BuildRecord::*m :
       {&BuildRecord::compiler, &BuildRecord::build_type, &BuildRecord::cxx_flags}) {
    BuildRecord c = b;
    c.*m = "other";
    EXPECT_NE(build_fingerprint(c), fp);
  }
  BuildRecord v = b;
  v.version = "0.2.0";
  EXPECT_NE(build_fingerprint(v), fp);
}

JobRecord fingerprinted_record() {
  JobRecord r = test::identity_record("sphere_grid", "64x48", "pcf_box/k=3");
  r.gl_renderer = kRenderer;
  r.gl_version = kVersion;
  r.host = sample_host();
  r.host.fingerprint = host_fingerprint(r.host, r.gl_renderer, r.gl_version);
  r.build = {"0.1.0",      "GNU 12.2.0", "Release",    "-O3 -DNDEBUG",
             std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  r.build.fingerprint = build_fingerprint(r.build);
  return r;
}

TEST(HostRecord, RoundTrips) {
  const json j = fingerprinted_record().to_json();
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  const json& h = j["host"];
  EXPECT_EQ(h["cpu"]["model"], "AMD EPYC 7B13");
  EXPECT_EQ(h["cpu"]["isa"], json::array({"sse4.2", "avx", "avx2", "fma"}));
  EXPECT_EQ(h["cpu"]["logical_cores"], 2);
  EXPECT_EQ(h["gl_stack"],
            json({{"mesa_version", "22.3.6"}, {"llvm_version", "15.0.6"}, {"vector_bits", 256}}));
  EXPECT_EQ(h["env"], json({{"LP_NUM_THREADS", "2"}}));
  EXPECT_EQ(h["os"], "Debian GNU/Linux 12 (bookworm)");
  EXPECT_EQ(h["embree_isa"], "avx2");
  EXPECT_EQ(h["fingerprint"], back.host.fingerprint.value());
  EXPECT_EQ(j["build"]["compiler"], "GNU 12.2.0");
  EXPECT_EQ(j["build"]["fingerprint"].get<std::string>().size(), 16u);
  // env is written even when no knob is set.
  JobRecord quiet = fingerprinted_record();
  quiet.host.env.clear();
  EXPECT_EQ(quiet.to_json()["host"]["env"], json::object());
}

// A record written before host fingerprints: host and build as they were.
TEST(HostRecord, OldRecordStillReads) {
  json j = fingerprinted_record().to_json();
  j["host"] = {{"hardware_threads", 2}, {"name", "vm"}};
  j["build"] = {{"version", "0.1.0"}};
  const JobRecord r = JobRecord::from_json(j);
  EXPECT_EQ(r.host.hardware_threads, 2);
  EXPECT_EQ(r.host.name, "vm");
  EXPECT_FALSE(r.host.cpu.has_value());
  EXPECT_FALSE(r.host.fingerprint.has_value());
  EXPECT_TRUE(r.host.env.empty());
  EXPECT_FALSE(r.build.fingerprint.has_value());
  EXPECT_EQ(r.build.version, "0.1.0");
}

TEST(HostRecord, IllTypedMembersAreNamedByPointer) {
  const json good = fingerprinted_record().to_json();
  const std::pair<const char*, json> cases[] = {
      {"/host/cpu/isa", "avx2"},       {"/host/cpu/logical_cores", "2"},
      {"/host/env/LP_NUM_THREADS", 2}, {"/host/gl_stack/vector_bits", "256"},
      {"/host/fingerprint", 12},       {"/build/cxx_flags", json::array()},
  };
  for (const auto& [pointer, value] : cases) {
    json j = good;
    j[json::json_pointer(pointer)] = value;
    try {
      JobRecord::from_json(j);
      ADD_FAILURE() << pointer << " was read";
    } catch (const RecordError& e) {
      EXPECT_EQ(e.pointer(), pointer) << e.what();
    }
  }
}

TEST(HostInfo, ParsesCpuinfoAndOsRelease) {
  EXPECT_EQ(cpuinfo_model_name("processor\t: 0\nvendor_id\t: AuthenticAMD\n"
                               "model name\t: AMD EPYC 7B13\nflags\t\t: fpu\n\n"
                               "processor\t: 1\nmodel name\t: AMD EPYC 7B13\n"),
            "AMD EPYC 7B13");
  EXPECT_FALSE(cpuinfo_model_name("processor\t: 0\nCPU implementer\t: 0x41\n").has_value());
  EXPECT_FALSE(cpuinfo_model_name("model name\t:\n").has_value());
  EXPECT_FALSE(cpuinfo_model_name("").has_value());
  EXPECT_EQ(os_release_pretty_name("NAME=\"Debian GNU/Linux\"\n"
                                   "PRETTY_NAME=\"Debian GNU/Linux 12 (bookworm)\"\nID=debian\n"),
            "Debian GNU/Linux 12 (bookworm)");
  EXPECT_EQ(os_release_pretty_name("PRETTY_NAME='Alpine Linux v3.19'"), "Alpine Linux v3.19");
  EXPECT_EQ(os_release_pretty_name("PRETTY_NAME=Plain"), "Plain");
  EXPECT_FALSE(os_release_pretty_name("ID=debian\n").has_value());
}

TEST(HostInfo, DescribesThisMachine) {
  unsetenv("LP_NATIVE_VECTOR_WIDTH");
  setenv("LP_PERF", "no_tex", 1);
  const HostRecord h = describe_host(kRenderer, kVersion, "avx2");
  unsetenv("LP_PERF");
  ASSERT_TRUE(h.cpu.has_value());
  EXPECT_GE(h.cpu->logical_cores, 1);
  EXPECT_GE(h.hardware_threads, 1);
  for (const auto& feature : h.cpu->isa)
    EXPECT_NE(std::find(std::begin(kCpuIsaFeatures), std::end(kCpuIsaFeatures), feature),
              std::end(kCpuIsaFeatures))
        << feature;
#if defined(__x86_64__)
  EXPECT_FALSE(h.cpu->model.empty());
  EXPECT_FALSE(h.cpu->isa.empty());  // every x86-64 CPU this runs on has SSE4.2 or better
#endif
  EXPECT_EQ(h.env.at("LP_PERF"), "no_tex");
  EXPECT_EQ(h.env.count("LP_NATIVE_VECTOR_WIDTH"), 0u);
  EXPECT_EQ(h.gl_stack->vector_bits, 256);
  EXPECT_EQ(h.embree_isa, "avx2");
  ASSERT_TRUE(h.fingerprint.has_value());
  EXPECT_EQ(*h.fingerprint, host_fingerprint(h, kRenderer, kVersion));
  // The same machine and environment: the same fingerprint; the knob: another.
  EXPECT_EQ(describe_host(kRenderer, kVersion, "sse4.2").fingerprint,
            host_fingerprint(
                [&] {
                  HostRecord without = h;
                  without.env.erase("LP_PERF");
                  return without;
                }(),
                kRenderer, kVersion));
  EXPECT_NE(describe_host(kRenderer, kVersion, "avx2").fingerprint, h.fingerprint);

  const BuildRecord b = describe_build();
  EXPECT_FALSE(b.version.empty());
  EXPECT_FALSE(b.compiler.value_or("").empty());
  EXPECT_EQ(b.fingerprint, build_fingerprint(b));
}

}  // namespace
}  // namespace sb
