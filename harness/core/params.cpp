#include "core/params.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/json_reader.h"

namespace sb::core {

ParamSpec int_param(std::string name, int def, int min, int max, std::string doc) {
  return {std::move(name),
          ParamType::Int,
          def,
          double(min),
          double(max),
          {},
          std::move(doc),
          {},
          false,
          {},
          {},
          false,
          Decides::Both,
          {}};
}
ParamSpec float_param(std::string name, double def, double min, double max, std::string doc) {
  return {std::move(name), ParamType::Float, def, min, max, {}, std::move(doc), {}, false, {}, {},
          false,           Decides::Both,    {}};
}
ParamSpec bool_param(std::string name, bool def, std::string doc) {
  return {std::move(name), ParamType::Bool, def, 0, 1, {}, std::move(doc), {}, false, {}, {},
          false,           Decides::Both,   {}};
}
ParamSpec choice_param(std::string name, std::string def, std::vector<std::string> choices,
                       std::string doc) {
  return {std::move(name),
          ParamType::Choice,
          std::move(def),
          0,
          0,
          std::move(choices),
          std::move(doc),
          {},
          false,
          {},
          {},
          false,
          Decides::Both,
          {}};
}

ParamSpec string_param(std::string name, std::string def, std::string doc) {
  return {std::move(name),
          ParamType::String,
          std::move(def),
          0,
          0,
          {},
          std::move(doc),
          {},
          false,
          {},
          {},
          false,
          Decides::Both,
          {}};
}

ParamSpec path_param(std::string name, std::string doc) {
  ParamSpec s = string_param(std::move(name), "", std::move(doc));
  s.is_path = true;
  return s;
}

ParamSpec odd(ParamSpec spec) {
  spec.rule = [](const nlohmann::json& v) {
    return v.get<long long>() % 2 != 0 ? std::string() : std::string("an odd integer");
  };
  spec.rule_doc = "odd";
  return spec;
}

ParamSpec with_sentinel(ParamSpec spec, double value) {
  spec.sentinel = value;
  return spec;
}

ParamSpec deciding(ParamSpec spec, Decides what) {
  spec.decides = what;
  return spec;
}

ParamSpec as_map_size(ParamSpec spec) {
  spec.map_size = true;
  return spec;
}

std::string to_string(ParamType t) {
  switch (t) {
    case ParamType::Int:
      return "integer";
    case ParamType::Float:
      return "number";
    case ParamType::Bool:
      return "boolean";
    case ParamType::Choice:
      return "choice";
    case ParamType::String:
      return "string";
  }
  return "?";
}

std::string to_string(Decides d) {
  switch (d) {
    case Decides::None:
      return "none";
    case Decides::Error:
      return "error";
    case Decides::Timing:
      return "timing";
    case Decides::Both:
      return "both";
  }
  return "?";
}

const nlohmann::json& Params::get(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("parameter '" + name + "' was never declared");
  read_.insert(name);
  return *it;
}
std::vector<std::string> Params::unread() const {
  std::vector<std::string> out;
  for (auto it = values_.begin(); it != values_.end(); ++it)
    if (!read_.count(it.key())) out.push_back(it.key());
  return out;
}
int Params::get_int(const std::string& name) const { return get(name).get<int>(); }
float Params::get_float(const std::string& name) const { return get(name).get<float>(); }
bool Params::get_bool(const std::string& name) const { return get(name).get<bool>(); }
std::string Params::get_string(const std::string& name) const {
  return get(name).get<std::string>();
}

namespace {

// Fails with an InputError naming `file`, the pointer and the parameter.
JsonReader param_reader(const std::string& file, const std::string& name) {
  return JsonReader([file, name](const std::string& pointer, const std::string& problem) {
    throw InputError(file, pointer, "parameter '" + name + "': " + problem);
  });
}

// A bound of an Int spec as an integer (the default bounds are ±1e300).
std::int64_t int_bound(double v) {
  if (v <= double(std::numeric_limits<std::int64_t>::min()))
    return std::numeric_limits<std::int64_t>::min();
  if (v >= double(std::numeric_limits<std::int64_t>::max()))
    return std::numeric_limits<std::int64_t>::max();
  return static_cast<std::int64_t>(v);
}

}  // namespace

nlohmann::json read_param_value(const JsonReader& r, const ParamSpec& spec,
                                const nlohmann::json& value, const std::string& pointer,
                                bool whole_floats) {
  nlohmann::json v;
  switch (spec.type) {
    case ParamType::Int:
      v = r.integer(value, pointer, int_bound(spec.min), int_bound(spec.max), whole_floats);
      break;
    case ParamType::Float:
      v = r.number(value, pointer, spec.min, spec.max);
      break;
    case ParamType::Bool:
      v = r.boolean(value, pointer);
      break;
    case ParamType::String:
      v = r.string(value, pointer);
      if (spec.is_path && v.get_ref<const std::string&>().empty())
        r.refuse(value, pointer, "a file path");
      break;
    case ParamType::Choice:
      v = r.choice(value, pointer, spec.choices);
      break;
  }
  if (spec.rule) {
    const std::string expected = spec.rule(v);
    if (!expected.empty()) r.refuse(value, pointer, expected);
  }
  return v;
}

nlohmann::json check_param_value(const ParamSpec& spec, const nlohmann::json& value,
                                 const std::string& file, const std::string& pointer) {
  return read_param_value(param_reader(file, spec.name), spec, value, pointer, true);
}

Params resolve_params(const std::vector<ParamSpec>& specs, const nlohmann::json& given,
                      const std::string& file, const std::string& pointer) {
  nlohmann::json out = nlohmann::json::object();
  const JsonReader r([&file](const std::string& where, const std::string& problem) {
    throw InputError(file, where, problem);
  });
  if (!given.is_null()) {
    r.object(given, pointer, "parameters");
    std::vector<std::string> names;
    names.reserve(specs.size());
    for (const auto& s : specs) names.push_back(s.name);
    r.only_keys(given, pointer, names, "parameter");
  }
  for (const auto& s : specs) {
    if (given.is_object() && given.contains(s.name))
      out[s.name] = check_param_value(s, given.at(s.name), file, pointer + "/" + s.name);
    else if (s.is_path && s.default_value == "")
      r.member(nlohmann::json::object(), pointer, s.name);  // missing: fails
    else
      out[s.name] = s.default_value;
  }
  return Params(std::move(out));
}

}  // namespace sb::core
