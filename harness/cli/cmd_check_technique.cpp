// `shadowbench check-technique NAME`: the timing contract's checks
// (run/timing_contract.h), the ones every built-in technique is held to, on
// one technique, built in or a plugin's, on a small scene.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/experiment.h"
#include "core/error.h"
#include "gl/context.h"
#include "run/timing_contract.h"

namespace sb::cli {

using core::InputError;
using core::kExitJobsFailed;
using core::kExitOk;

namespace {

constexpr int kWidth = 96;
constexpr int kHeight = 72;

struct CheckTechniqueArgs {
  std::string name;
  std::vector<std::string> params;  // KEY=VALUE
  std::string plugins;
  std::string backend = "osmesa";
};

// NAME with --param's values, checked as a config's technique is (names,
// types, ranges, rules across parameters).
config::TechniqueVariant variant_of(const CheckTechniqueArgs& a, const plugin::Registry& r) {
  nlohmann::json params = nlohmann::json::object();
  for (const std::string& p : a.params) {
    const size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("", "--param " + p, "expected KEY=VALUE (a JSON value, or a string)");
    const std::string value = p.substr(eq + 1);
    const nlohmann::json parsed = nlohmann::json::parse(value, nullptr, false);
    params[p.substr(0, eq)] = parsed.is_discarded() ? nlohmann::json(value) : parsed;
  }
  const nlohmann::json experiment = {{"name", "check-technique"},
                                     {"scenes", {{{"type", "sphere_grid"}}}},
                                     {"techniques", {{{"name", a.name}, {"params", params}}}},
                                     {"resolutions", {{kWidth, kHeight}}}};
  const std::vector<config::TechniqueVariant> variants =
      config::parse_experiment(experiment, "check-technique", r).techniques;
  if (variants.size() != 1)
    throw InputError("", "check-technique", "expected one variant; give each --param one value");
  return variants.front();
}

int cmd_check_technique(const CheckTechniqueArgs& a) {
  const auto started = std::chrono::steady_clock::now();
  const plugin::Registry r = load_registry(a.plugins);
  const config::TechniqueVariant tv = variant_of(a, r);
  const std::unique_ptr<gl::Context> context =
      gl::create_context(gl::backend_from_string(a.backend));
  // The square light, or else a segment or the sun: the first the
  // technique's needs accept.
  run::ContractLight light = run::ContractLight::Square;
  auto stage = std::make_unique<run::ContractStage>(run::contract_scene(light), kWidth, kHeight,
                                                    std::vector{tv.info}, r);
  for (const run::ContractLight other : {run::ContractLight::Linear, run::ContractLight::Sun}) {
    if (stage->skip_reason(0).empty()) break;
    auto tried = std::make_unique<run::ContractStage>(run::contract_scene(other), kWidth, kHeight,
                                                      std::vector{tv.info}, r);
    if (tried->skip_reason(0).empty()) {
      light = other;
      stage = std::move(tried);
    }
  }
  std::printf("check-technique %s (family %s) on a 2x2 sphere grid with a %s light at %dx%d:\n",
              tv.name.c_str(), tv.info->family.c_str(), run::to_string(light), kWidth, kHeight);
  if (!stage->skip_reason(0).empty()) {
    std::printf("SKIP  the scene cannot serve it: %s\n", stage->skip_reason(0).c_str());
    return kExitJobsFailed;
  }
  // `none` and the controls are V = 1 anywhere: nothing they draw moves.
  const bool expect_change = tv.info->name != "none" && tv.info->family != "control";
  const std::vector<run::ContractCheck> checks = run::check_timing_contract(
      *stage, [&] { return tv.info->create(tv.params); }, expect_change, tv.info->temporal);
  int failed = 0;
  for (const run::ContractCheck& c : checks) {
    std::printf("%s  %s\n", c.passed() ? "PASS" : "FAIL", c.name.c_str());
    if (!c.passed()) {
      std::printf("      %s\n", c.failure.c_str());
      ++failed;
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("%d passed, %d failed (%.1f s)\n", int(checks.size()) - failed, failed, seconds);
  return failed == 0 ? kExitOk : kExitJobsFailed;
}

}  // namespace

void add_check_technique_command(CommandLine& cl) {
  const auto a = std::make_shared<CheckTechniqueArgs>();
  CLI::App* check = cl.add_command(
      cl.app(), "check-technique",
      "Check one technique against the timing contract, as every built-in is: prepare() keeps "
      "nothing of the light or the camera (a frame after either moved equals one prepared after "
      "the move), every frame writes V in [0,1] into every pixel, frames are deterministic and "
      "leave the G-buffer alone. On a 2x2 sphere grid at 96x72; prints PASS or FAIL per check "
      "and exits 0 when all pass, 1 when one fails, 2 for a bad NAME or --param.",
      "shadowbench check-technique my_pcf --plugins my_pcf/build",
      [a] { return cmd_check_technique(*a); });
  add_argument(check, "NAME", a->name, "the technique (shadowbench list names them)")->required();
  check
      ->add_option("--param", a->params,
                   "KEY=VALUE: a parameter of the technique (a JSON value, or a string); "
                   "repeatable, the defaults otherwise")
      ->type_name("KEY=VALUE")
      ->default_str("");  // not "[]"
  add_plugins(check, a->plugins);
  add_choice(check, "--backend", a->backend, {"osmesa", "egl"},
             "the GL backend: OSMesa (llvmpipe, anywhere) or EGL (a GPU if there is one)");
}

}  // namespace sb::cli
