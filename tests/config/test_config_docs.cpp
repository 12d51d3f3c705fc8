// The config blocks' tables in docs/config.md are generated from the blocks'
// declarations (config/config_blocks.h), and those declarations say what an
// Experiment holds: each default is the value a config without the key gets.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "config/config_blocks.h"
#include "config_fixtures.h"

namespace sb {

using config::BlockKey;
using config::config_blocks;
using config::ConfigBlock;
using config::Experiment;
using config::markdown_config_blocks;
using config::parse_experiment;
using core::ParamType;

namespace {

const char* const kBegin = "<!-- generated: config blocks -->\n";
const char* const kEnd = "<!-- end generated -->\n";
const char* const kRegenerate =
    "regenerate it: SHADOWBENCH_UPDATE_DOCS=1 build/tests/config/test_config "
    "--gtest_filter='ConfigDocs.*'";

TEST(ConfigDocs, TheDocsHoldTheGeneratedTables) {
  const std::string path = std::string(SHADOWBENCH_SOURCE_DIR) + "/docs/config.md";
  std::stringstream file;
  file << std::ifstream(path).rdbuf();
  std::string text = file.str();
  const size_t begin = text.find(kBegin);
  const size_t end = text.find(kEnd);
  ASSERT_NE(begin, std::string::npos) << path << " lacks " << kBegin;
  ASSERT_NE(end, std::string::npos) << path << " lacks " << kEnd;
  const size_t from = begin + std::string(kBegin).size();
  const std::string generated = markdown_config_blocks();
  if (std::getenv("SHADOWBENCH_UPDATE_DOCS") != nullptr) {
    text.replace(from, end - from, generated);
    std::ofstream(path) << text;
    return;
  }
  EXPECT_EQ(text.substr(from, end - from), generated) << kRegenerate;
}

nlohmann::json config_with(const nlohmann::json& blocks) {
  nlohmann::json c = {
      {"scenes", {{{"type", "sphere_grid"}}}}, {"techniques", {"none"}}, {"resolutions", {{8, 8}}}};
  c.update(blocks);
  return c;
}

TEST(ConfigDocs, EachDefaultIsWhatAConfigWithoutTheKeyGets) {
  nlohmann::json empty_blocks = nlohmann::json::object();
  for (const ConfigBlock& b : config_blocks()) empty_blocks[b.name] = nlohmann::json::object();
  const Experiment e = parse_experiment(config_with(empty_blocks), "c.json", test::registry());
  for (const ConfigBlock& b : config_blocks())
    for (const BlockKey& k : b.keys)
      EXPECT_EQ(k.value(e), k.spec.default_value) << b.pointer() << "/" << k.spec.name;
}

TEST(ConfigDocs, EachKeyIsStoredWhereItIsRead) {
  for (const ConfigBlock& b : config_blocks())
    for (const BlockKey& k : b.keys) {
      if (!k.store) continue;
      // A value other than the default, within the accepted ones.
      nlohmann::json v;
      switch (k.spec.type) {
        case ParamType::Int:
          v = static_cast<long long>(k.spec.max);
          break;
        case ParamType::Float:
          v = k.spec.max;
          break;
        case ParamType::Bool:
          v = !k.spec.default_value.get<bool>();
          break;
        case ParamType::Choice:
          v = k.spec.choices.back();
          break;
        case ParamType::String:
          continue;  // embree_config: its syntax is checked elsewhere
      }
      Experiment e;
      if (b.present) b.present(e);
      k.store(e, v);
      EXPECT_EQ(k.value(e), v) << b.pointer() << "/" << k.spec.name;
    }
}

}  // namespace
}  // namespace sb
