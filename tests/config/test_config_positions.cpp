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

namespace sb::test_config_positions {

using config::Experiment;
using config::load_experiment;
using core::InputError;
using core::TextPosition;
using plugin::Registry;

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
    // A sweep's bad value is placed at its element of the list, not at the list.
    {"swept_parameter", R"("k": 5)", R"("k": [3, 4, 5])", "4", "/techniques/1/params/k/1"},
    {"swept_parameter_type", R"("k": 5)", R"("k": [3, "five"])", "\"five\"",
     "/techniques/1/params/k/1"},
    {"swept_scene_parameter", R"("grid": 2)", R"("grid": [2, 0])", "0", "/scenes/0/params/grid/1"},
    // An unknown parameter is wrong as a key: placed at it, not at an element.
    {"swept_unknown_parameter", R"("k": 5)", R"("kk": [3, 5])", "[3, 5]",
     "/techniques/1/params/kk"},
};

// "LINE:COL" of the byte `offset` of `text`, both from 1.
std::string line_col(const std::string& text, size_t offset) {
  if (offset == 0) return "1:1";
  const size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(offset), '\n'));
  const size_t line_start = text.rfind('\n', offset - 1);
  const size_t col = line_start == std::string::npos ? offset + 1 : offset - line_start;
  return std::to_string(line) + ":" + std::to_string(col);
}

// kValid with `from` replaced by `to`, which starts at `at` (npos when
// `from` is not there).
std::string edited(const char* from, const char* to, size_t& at) {
  std::string text = kValid;
  at = text.find(from);
  if (at != std::string::npos) text.replace(at, std::string(from).size(), to);
  return text;
}

// The InputError loading `text` throws (a test failure when it loads).
InputError load_error(const std::string& name, const std::string& text) {
  try {
    load_experiment(write_temp(name + ".json", text), registry());
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << name << ": no error";
  return InputError("", "", "");
}

class ConfigPositions : public ::testing::TestWithParam<Case> {};

TEST_P(ConfigPositions, TheMessageNamesTheValuesLineAndColumn) {
  const Case& c = GetParam();
  size_t at = 0;
  const std::string text = edited(c.from, c.to, at);
  ASSERT_NE(at, std::string::npos) << c.from;
  const std::string to = c.to;
  const size_t token = at + to.rfind(c.token);  // the last: "warmup": 1 after "warmup": 0
  const InputError e = load_error(c.name, text);
  const std::string expected = e.file() + ":" + line_col(text, token) + " (" + c.pointer + "): ";
  EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << "expected " << expected << "...\n"
                                                          << e.what();
  EXPECT_EQ(e.where(), c.pointer);
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

// A missing required key has no place of its own: the message is placed at
// the object it is missing from, names that object's pointer and says which
// key is missing.
struct MissingCase {
  const char* name;
  const char* from;     // replaced in kValid...
  const char* to;       // ...by this
  const char* object;   // the start of the object the key is missing from, in `to`
  const char* pointer;  // that object's pointer
  const char* key;
};

const MissingCase kMissing[] = {
    {"scene_type", R"({"type": "sphere_grid", "params": {"grid": 2}})",
     R"({"params": {"grid": 2}})", R"({"params")", "/scenes/0", "type"},
    {"technique_name", R"({"name": "pcf_box", "params": {"k": 5, "size": 256}})",
     R"({"params": {"k": 5, "size": 256}})", R"({"params")", "/techniques/1", "name"},
    {"resolutions", R"(  "resolutions": [[64, 48], "32x24"],)", "", "{", "/", "resolutions"},
};

class MissingKeyPositions : public ::testing::TestWithParam<MissingCase> {};

TEST_P(MissingKeyPositions, TheMessageNamesTheObjectAndTheKey) {
  const MissingCase& c = GetParam();
  size_t at = 0;
  const std::string text = edited(c.from, c.to, at);
  ASSERT_NE(at, std::string::npos) << c.from;
  const size_t object = std::string(c.object) == "{" ? 0 : at + std::string(c.to).find(c.object);
  const InputError e = load_error(std::string("missing_") + c.name, text);
  EXPECT_EQ(std::string(e.what()), e.file() + ":" + line_col(text, object) + " (" + c.pointer +
                                       "): missing required key \"" + c.key + "\" in this object");
  EXPECT_EQ(e.where(), c.pointer);
}

INSTANTIATE_TEST_SUITE_P(Config, MissingKeyPositions, ::testing::ValuesIn(kMissing),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// Nesting deeper than the cap (64) is placed at the bracket that goes one
// level too deep: here the root object is level 1 and "deep"'s arrays levels
// 2 on, so the 64th '[' is level 65.
TEST(ConfigPositions, TooDeepNestingIsPlacedAtTheBracketPastTheCap) {
  const std::string text = "{\n  \"name\": \"deep\",\n  \"deep\": " + std::string(80, '[') +
                           std::string(80, ']') + "\n}";
  const size_t bracket = text.find('[') + 63;
  std::string pointer = "/deep";
  for (int i = 0; i < 63; ++i) pointer += "/0";
  const InputError e = load_error("too_deep", text);
  EXPECT_EQ(std::string(e.what()), e.file() + ":" + line_col(text, bracket) + " (" + pointer +
                                       "): nested deeper than 64 levels");
  EXPECT_EQ(e.where(), pointer);
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
}  // namespace sb::test_config_positions
