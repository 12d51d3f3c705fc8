// Every InputError about a config value names its line and column, as
// "file:LINE:COL (/pointer): what", also when the value is found wrong after
// the JSON is parsed (a technique parameter, a scene type, a resolution). The
// expected line and column are found in each fixture's own text: the place
// of the offending value, whatever the reader's messages say.
#include <gtest/gtest.h>

#include <algorithm>

#include "config/experiment.h"
#include "config_fixtures.h"
#include "core/error.h"

namespace sb {
namespace {

const Registry& registry() { return test::registry(); }

std::string write_temp(const std::string& name, const std::string& text) {
  return test::write_temp("shadowbench_test_config_positions", name, text);
}

// A config over several lines, each block on a line of its own, so that a
// wrong line number shows.
const char* const kValid = R"({
  "name": "positions",
  "scenes": [
    {"type": "sphere_grid", "params": {"grid": 2}}
  ],
  "techniques": [
    "none",
    {"name": "pcf_box", "params": {"k": 5, "size": 256}}
  ],
  "resolutions": [[64, 48], "32x24"],
  "frames": {"warmup": 0, "timed": 2},
  "reference": {"spp": 16, "seed": 3},
  "stability": {"flicker_frames": 4},
  "metrics": {"distance_thirds": false},
  "limits": {"job_seconds": 60}
})";

struct Case {
  const char* name;
  const char* from;     // replaced in kValid...
  const char* to;       // ...by this
  const char* token;    // the offending value, found in `to`
  const char* pointer;  // the pointer the message names
};

const Case kCases[] = {
    {"frames", R"("timed": 2)", R"("timed": 0)", "0", "/frames/timed"},
    {"reference", R"("spp": 16)", R"("spp": 0)", "0", "/reference/spp"},
    {"stability", R"("flicker_frames": 4)", R"("flicker_frames": 1)", "1",
     "/stability/flicker_frames"},
    {"metrics", R"("distance_thirds": false)", R"("distance_thirds": "yes")", "\"yes\"",
     "/metrics/distance_thirds"},
    {"limits", R"("job_seconds": 60)", R"("job_seconds": 0.5)", "0.5", "/limits/job_seconds"},
    {"technique_parameter", R"("k": 5)", R"("k": 4)", "4", "/techniques/1/params/k"},
    {"resolution", R"("32x24")", R"("32y24")", "\"32y24\"", "/resolutions/1"},
    {"scene_type", R"("type": "sphere_grid")", R"("type": "spheres")", "\"spheres\"",
     "/scenes/0/type"},
    {"unknown_key", R"("frames": {"warmup": 0,)", R"("frames": {"warmup": 0, "timd": 3,)", "3",
     "/frames/timd"},
    {"duplicate_key", R"("frames": {"warmup": 0,)", R"("frames": {"warmup": 0, "warmup": 1,)", "1",
     "/frames/warmup"},
};

// "LINE:COL" of the byte `offset` of `text`, both from 1.
std::string line_col(const std::string& text, size_t offset) {
  const size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(offset), '\n'));
  const size_t line_start = text.rfind('\n', offset - 1);
  const size_t col = line_start == std::string::npos ? offset + 1 : offset - line_start;
  return std::to_string(line) + ":" + std::to_string(col);
}

class ConfigPositions : public ::testing::TestWithParam<Case> {};

TEST_P(ConfigPositions, TheMessageNamesTheValuesLineAndColumn) {
  const Case& c = GetParam();
  std::string text = kValid;
  const size_t at = text.find(c.from);
  ASSERT_NE(at, std::string::npos) << c.from;
  text.replace(at, std::string(c.from).size(), c.to);
  const std::string to = c.to;
  const size_t token = at + to.rfind(c.token);  // the last: "warmup": 1 after "warmup": 0
  const std::string path = write_temp(std::string(c.name) + ".json", text);
  try {
    load_experiment(path, registry());
    FAIL() << c.name << ": no error";
  } catch (const InputError& e) {
    const std::string expected = path + ":" + line_col(text, token) + " (" + c.pointer + "): ";
    EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << "expected " << expected << "...\n"
                                                            << e.what();
    EXPECT_EQ(e.where(), c.pointer);
  }
}

INSTANTIATE_TEST_SUITE_P(Config, ConfigPositions, ::testing::ValuesIn(kCases),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// A problem found after loading (a plan's, a scene build's) is placed the
// same way: Experiment::position and SceneVariant::position.
TEST(ConfigPositions, TheLoadedExperimentKnowsWhereItsEntriesAre) {
  const std::string text = kValid;
  const Experiment e = load_experiment(write_temp("valid.json", text), registry());
  const size_t pcf = text.find(R"({"name": "pcf_box")");
  const TextPosition t = e.position("/techniques/1");
  EXPECT_EQ(std::to_string(t.line) + ":" + std::to_string(t.column), line_col(text, pcf));
  const TextPosition s = e.scenes[0].position;
  EXPECT_EQ(std::to_string(s.line) + ":" + std::to_string(s.column),
            line_col(text, text.find(R"({"type": "sphere_grid")")));
  // A missing member is placed at the object it is missing from.
  const TextPosition missing = e.position("/frames/control");
  EXPECT_EQ(std::to_string(missing.line) + ":" + std::to_string(missing.column),
            line_col(text, text.find(R"({"warmup")")));
}

// The key's place is found by walking the text, which trusts the grammar and
// recurses: after a key twice, text too deep for it is not walked.
TEST(ConfigPositions, AKeyTwiceBeforeDeepNestingIsPlacedByPointerAlone) {
  const std::string text = R"({"name": "a", "name": "b", "x": )" + std::string(200000, '[') +
                           std::string(200000, ']') + "}";
  try {
    load_experiment(write_temp("twice_deep.json", text), registry());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/name");
    EXPECT_NE(std::string(e.what()).find("appears twice"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sb
