#pragma once
// Parameters declared as data: a technique or scene lists its parameters with
// types, defaults and ranges; configs are checked against that list before
// any GL context exists, and unknown keys are errors.
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace sb::core {

class JsonReader;

enum class ParamType { Int, Float, Bool, Choice, String };

// Which of a job's numbers a setting decides: its errors (what is rendered
// and measured against what), its timings, both, or none (where files go, how
// long a job may take). A job's identity, the spec a rerun compares
// (run/job_identity.h), is generated from these declarations: every setting
// that decides something is in it, and no other.
enum class Decides { None, Error, Timing, Both };

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Float;
  nlohmann::json default_value;
  double min = -1e300;  // inclusive, for Int and Float
  double max = 1e300;
  std::vector<std::string> choices;  // for Choice
  std::string doc;
  // Optional extra rule on a value that already has the right type and range:
  // returns "" when fine, else what was expected ("an odd integer").
  std::function<std::string(const nlohmann::json&)> rule;
  // String parameters naming a file: the config layer resolves them relative
  // to the config file's folder.
  bool is_path = false;
  std::string rule_doc;  // what `rule` accepts, for the docs: "odd", "2 or 4"
  // A Float value that means "chosen automatically" (sigma 0: from k), where
  // V is not a continuous function of the value: the stability suite takes
  // no finite difference there.
  std::optional<double> sentinel;
  // The side of a shadow map the technique renders, in texels: techniques
  // compared in one experiment should render maps of one size, or time and
  // error compare unequal work (config/map_sizes.h warns). Declared once,
  // where the parameter is (sb::techniques::depth_map_params).
  bool map_size = false;
  // What it decides (Decides). A technique's or a scene's parameters decide
  // both unless declared otherwise. A path parameter (is_path) is part of a
  // job's identity by the content of the file it names, not by the path.
  Decides decides = Decides::Both;
  // The parameter that turns this one's feature on, or "" for none: a Bool
  // ("contact" for contact_length) or a Choice whose value "none" is off
  // ("denoiser" for a denoiser's own): while it is off this one changes
  // nothing, and the stability suite takes no sensitivity to it.
  std::string enabled_by;
};

// Adds the rule "odd integer" to an Int parameter.
ParamSpec odd(ParamSpec spec);
// Marks `value` of a Float parameter as a sentinel (ParamSpec::sentinel).
ParamSpec with_sentinel(ParamSpec spec, double value);
// Marks an Int parameter as a shadow map's side (ParamSpec::map_size).
ParamSpec as_map_size(ParamSpec spec);
// Declares what the parameter decides (ParamSpec::decides).
ParamSpec deciding(ParamSpec spec, Decides what);

ParamSpec int_param(std::string name, int def, int min, int max, std::string doc);
ParamSpec float_param(std::string name, double def, double min, double max, std::string doc);
ParamSpec bool_param(std::string name, bool def, std::string doc);
ParamSpec choice_param(std::string name, std::string def, std::vector<std::string> choices,
                       std::string doc);
ParamSpec string_param(std::string name, std::string def, std::string doc);
// A file path; "" as default means the parameter is required.
ParamSpec path_param(std::string name, std::string doc);

std::string to_string(ParamType t);
// "none", "error", "timing", "both".
std::string to_string(Decides d);

// Resolved parameter values (defaults filled in, every value checked).
// Params remembers which of them a get_*() has read, so that a declared
// parameter no code reads can be reported (config/unread_params.h).
class Params {
 public:
  Params() = default;
  explicit Params(nlohmann::json values) : values_(std::move(values)) {}
  int get_int(const std::string& name) const;
  float get_float(const std::string& name) const;
  bool get_bool(const std::string& name) const;
  std::string get_string(const std::string& name) const;
  // The values as JSON; reading them here does not count as reading.
  const nlohmann::json& json() const { return values_; }
  // The parameters no get_*() has read, by name. A copy starts
  // with the reads of its source; Params(json()) starts with none.
  std::vector<std::string> unread() const;

 private:
  const nlohmann::json& get(const std::string& name) const;
  nlohmann::json values_ = nlohmann::json::object();
  mutable std::set<std::string> read_;
};

// Checks one scalar value against its spec; throws InputError naming `file`
// and `pointer` (the value's JSON pointer) with what was expected and found.
nlohmann::json check_param_value(const ParamSpec& spec, const nlohmann::json& value,
                                 const std::string& file, const std::string& pointer);

// The one check of a value against its spec (type, range or choices, then
// its rule), failing through `reader`, which says where and how. With
// `whole_floats` an Int may be written 2.0, as technique and scene
// parameters may; a config's own settings (config/config_blocks.h) may not.
nlohmann::json read_param_value(const JsonReader& reader, const ParamSpec& spec,
                                const nlohmann::json& value, const std::string& pointer,
                                bool whole_floats);

// Fills defaults into `given` (already-scalar values) and rejects unknown keys.
Params resolve_params(const std::vector<ParamSpec>& specs, const nlohmann::json& given,
                      const std::string& file, const std::string& pointer);

}  // namespace sb::core
