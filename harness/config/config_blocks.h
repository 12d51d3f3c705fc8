#pragma once
// The config's blocks of settings (frames, reference, stability, metrics,
// limits), each declared once as a table of keys with their type, default,
// accepted values and meaning, as techniques declare their parameters
// (core/params.h). The reader checks a config against these tables, and
// docs/config.md's tables of the blocks are generated from them
// (markdown_config_blocks; tests/config/test_config_docs.cpp keeps the file
// equal), so a range is written in one place.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/config_reader.h"
#include "config/experiment.h"
#include "core/params.h"

namespace sb::config {

// One key of a block.
struct BlockKey {
  // `decides`: which of a job's numbers the key decides, declared with the
  // key (core::Decides): a job's identity is generated from it
  // (config/identity.h, blocks_identity).
  BlockKey(core::Decides decides, core::ParamSpec spec_,
           std::function<void(Experiment&, const nlohmann::json&)> store_,
           std::function<nlohmann::json(const Experiment&)> value_, std::string type_doc_ = "",
           std::string accepted_doc_ = "")
      : spec(core::deciding(std::move(spec_), decides)),
        store(std::move(store_)),
        value(std::move(value_)),
        type_doc(std::move(type_doc_)),
        accepted_doc(std::move(accepted_doc_)) {}
  // Name, type, default, range or choices, rule, meaning and what it decides
  // (spec.decides). The default is what the Experiment holds when the key is
  // absent (a test checks it).
  core::ParamSpec spec;
  // Stores a checked value; null for a key read elsewhere (frames.control, a
  // technique entry, needs the registry).
  std::function<void(Experiment&, const nlohmann::json&)> store;
  // The Experiment's value, as the config would spell it.
  std::function<nlohmann::json(const Experiment&)> value;
  std::string type_doc;      // the docs' type when not the spec's ("technique")
  std::string accepted_doc;  // the docs' accepted values when not the spec's
  // Its part of a job's identity, when more than `value` (frames.control:
  // the technique's parameters and plugin); null: `value`.
  std::function<nlohmann::json(const Experiment&)> identity;
};

struct ConfigBlock {
  std::string name;  // the top-level key; its JSON pointer is "/" + name
  std::string what;  // for "expected frame counts (an object)"
  std::vector<BlockKey> keys;
  // Called when the block is present, before its keys are read (stability:
  // present, it turns the suite on).
  std::function<void(Experiment&)> present;
  // Rules across keys, after every key is read: the block as given, and the
  // reader to fail with.
  std::function<void(Experiment&, const nlohmann::json&, const ConfigReader&)> finish;
  // Whether its keys apply to `e` (stability: only when present); null:
  // always. A block not in effect is null in a job's identity.
  std::function<bool(const Experiment&)> in_effect;
  std::string pointer() const { return "/" + name; }
};

// frames, reference, stability, metrics, limits: in the order of docs/config.md.
const std::vector<ConfigBlock>& config_blocks();

// Reads every block `doc` holds into `e` (frames.control aside).
void read_config_blocks(const ConfigReader& r, const nlohmann::json& doc, Experiment& e);

// One Markdown table per block: | key | type | default | accepted | decides | meaning |.
std::string markdown_config_blocks();

}  // namespace sb::config
