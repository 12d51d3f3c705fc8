// libFuzzer target: an experiment config's bytes through the loader, as
// `shadowbench validate` reads them (JSON limits, schema, sweeps, technique
// parameters against the real plugins, unread-parameter warnings).
#include <cstddef>
#include <cstdint>
#include <string>

#include "config/experiment.h"
#include "config/json_file.h"
#include "config/unread_params.h"
#include "fuzz_input.h"
#include "plugin/registry.h"

namespace {

const sb::plugin::Registry& registry() {
  static const sb::plugin::Registry r = [] {
    sb::plugin::Registry loaded;
    loaded.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    return loaded;
  }();
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  (void)registry();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return sb::fuzz::expect_only_input_errors("fuzz_experiment", [&] {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const sb::config::Experiment e = sb::config::parse_experiment(
        sb::config::parse_json_text(text, "fuzz.json"), "fuzz.json", registry());
    (void)sb::config::unread_parameter_warnings(e);
  });
}
