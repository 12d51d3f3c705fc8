// SHA-256 (core/sha256.h) against FIPS 180-2's test vectors and coreutils'
// sha256sum, and a plugin module's identity (plugin/plugin_identity.h): its
// name in its folder, its size and the hash of its bytes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../common/cli_run.h"
#include "core/sha256.h"
#include "plugin/plugin_identity.h"

namespace sb {

using core::sha256_file_hex;
using core::sha256_hex;
using plugin::identify_plugin;
using plugin::kPluginApiVersion;
using plugin::PluginIdentity;

namespace {

namespace fs = std::filesystem;

TEST(Sha256, MatchesTheStandardsVectors) {
  // FIPS 180-2, appendix B.1 and B.2, and the empty message.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

// sha256sum's digest of a file: an implementation other than ours.
std::string sha256sum(const fs::path& file) {
  const test::CliRun r = test::run_command("sha256sum '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.output.substr(0, 64);
}

// A file larger than one read block, with bytes of every value.
fs::path binary_file(const fs::path& dir) {
  const fs::path file = dir / "module.so";
  std::ofstream out(file, std::ios::binary);
  for (int i = 0; i < 200000; ++i) out.put(char((i * 7 + i / 256) & 255));
  return file;
}

TEST(Sha256, AFileHashesAsSha256sumSaysAcrossReadBlocks) {
  const fs::path file = binary_file(test::test_folder("shadowbench_test_sha256_"));
  EXPECT_EQ(sha256_file_hex(file.string()), sha256sum(file));
}

TEST(Sha256, AFileThatCannotBeReadHasNoHash) {
  EXPECT_EQ(sha256_file_hex("/nonexistent/shadowbench/module.so"), std::nullopt);
}

// A device never ends: a scene file named /dev/zero must not hang the run
// that identifies its jobs (tests/hostile, gltf_dev_zero).
TEST(Sha256, OnlyARegularFileIsHashed) {
  EXPECT_EQ(sha256_file_hex("/dev/zero"), std::nullopt);
  EXPECT_EQ(sha256_file_hex("/"), std::nullopt);
}

TEST(PluginIdentity, NamesTheFileInItsFolderItsSizeAndItsHash) {
  const fs::path file = binary_file(test::test_folder("shadowbench_test_plugin_identity_"));
  const PluginIdentity id = identify_plugin(file.string());
  EXPECT_EQ(id.file, "module.so");
  EXPECT_EQ(id.size, 200000);
  EXPECT_EQ(id.sha256, sha256sum(file));
  EXPECT_EQ(id.api_version, kPluginApiVersion);
}

}  // namespace
}  // namespace sb
