#include "e2e_util.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "config/experiment.h"
#include "metrics/image_io.h"
#include "plugin/registry.h"
#include "store/results_store.h"

namespace sb::test {

using config::Experiment;
using config::parse_experiment;
using core::ImageF;
using plugin::Registry;
using run::run_experiment;
using run::RunOptions;
using store::read_run_records;

namespace fs = std::filesystem;

namespace {
const Registry& registry() {
  static Registry r = [] {
    Registry reg;
    reg.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    return reg;
  }();
  return r;
}
}  // namespace

const nlohmann::json& RunOutput::record(const std::string& technique_variant) const {
  for (const auto& r : records)
    if (r["technique_variant"] == technique_variant) return r;
  throw std::runtime_error("no record for " + technique_variant);
}

ImageF RunOutput::visibility(const std::string& technique_variant) const {
  const auto& r = record(technique_variant);
  if (r["status"] != "ok") throw std::runtime_error(technique_variant + ": " + r.dump());
  return metrics::io::read_image(
      (fs::path(dir) / r["images"]["visibility"].get<std::string>()).string());
}

ImageF RunOutput::reference_visibility() const {
  return metrics::io::read_image(
      (fs::path(dir) / records.at(0)["images"]["reference_visibility"].get<std::string>())
          .string());
}

ImageF RunOutput::gbuffer_positions() const {
  return metrics::io::read_image(
      (fs::path(dir) / records.at(0)["images"]["gbuffer_positions"].get<std::string>()).string());
}

ImageF RunOutput::image(const nlohmann::json& record, const std::string& key) const {
  return metrics::io::read_image(
      (fs::path(dir) / record["images"][key].get<std::string>()).string());
}

std::vector<uint8_t> RunOutput::mask(const nlohmann::json& record,
                                     const std::string& region) const {
  const ImageF m = metrics::io::read_image(
      (fs::path(dir) / record["images"]["masks"][region].get<std::string>()).string());
  std::vector<uint8_t> out(m.pixel_count());
  for (std::size_t p = 0; p < out.size(); ++p)
    out[p] = m.data[p * static_cast<std::size_t>(m.channels)] > 0.5f ? 1 : 0;
  return out;
}

std::string process_temp_path(const std::string& name) {
  return (fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()))).string();
}

RunOutput run_config(const nlohmann::json& config, const std::string& name, gl::Backend backend,
                     bool fresh, bool write_gbuffer) {
  return run_config_with(
      config, name,
      [&](RunOptions& o) {
        o.backend = backend;
        o.write_gbuffer = write_gbuffer;
      },
      fresh);
}

RunOutput run_config_with(const nlohmann::json& config, const std::string& name,
                          const std::function<void(RunOptions&)>& adjust, bool fresh) {
  RunOutput out;
  out.dir = process_temp_path("shadowbench_e2e_" + name);
  if (fresh) fs::remove_all(out.dir);
  const Experiment e = parse_experiment(config, name + ".json", registry());
  RunOptions o;
  o.run_dir = out.dir;
  o.run_id = name;
  o.cache_dir = (fs::temp_directory_path() / "shadowbench_e2e_cache").string();
  o.quiet = true;
  adjust(o);
  out.summary = run_experiment(e, o);
  out.records = read_run_records(out.dir);
  return out;
}

RunOutput run_with_registry(const nlohmann::json& config, const Registry& registry,
                            const std::string& name) {
  RunOutput out;
  out.dir = process_temp_path("shadowbench_e2e_" + name);
  fs::remove_all(out.dir);
  const Experiment e = parse_experiment(config, name + ".json", registry);
  RunOptions o;
  o.run_dir = out.dir;
  o.run_id = name;
  o.cache_dir = "";
  o.quiet = true;
  o.write_images = false;
  out.summary = run_experiment(e, o);
  out.records = read_run_records(out.dir);
  return out;
}

std::string fresh_test_folder(const std::string& prefix) {
  const fs::path dir =
      process_temp_path(prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::vector<bool> ground_pixels(const ImageF& positions) {
  std::vector<bool> ground(positions.pixel_count());
  for (size_t i = 0; i < ground.size(); ++i)
    ground[i] = positions.data[i * 4 + 3] != 0.0f && std::abs(positions.data[i * 4 + 1]) < 1e-4f;
  return ground;
}

nlohmann::json small_scene(double light_size) {
  return {{"type", "sphere_grid"},
          {"params", {{"grid", 3}, {"light_size", light_size}}},
          {"camera", {{"eye", {0.0, 3.5, 5.5}}, {"target", {0.0, 0.6, 0.0}}}}};
}

}  // namespace sb::test
