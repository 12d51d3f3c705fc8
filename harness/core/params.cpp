#include "core/params.h"

#include <cmath>
#include <stdexcept>

#include "core/error.h"

namespace sb {

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
          {}};
}
ParamSpec float_param(std::string name, double def, double min, double max, std::string doc) {
  return {std::move(name), ParamType::Float, def, min, max, {}, std::move(doc), {}, false, {}, {}};
}
ParamSpec bool_param(std::string name, bool def, std::string doc) {
  return {std::move(name), ParamType::Bool, def, 0, 1, {}, std::move(doc), {}, false, {}, {}};
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
// A value as JSON text for a message. Values may hold bytes that are not
// UTF-8 (a scene spec from a command line): shown as U+FFFD, never thrown.
std::string quoted_json(const nlohmann::json& v) {
  return v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}
std::string describe(const nlohmann::json& v) {
  std::string kind = v.type_name();
  return kind + " " + quoted_json(v);
}
std::string number(double v) {
  nlohmann::json j = v;
  if (v == std::floor(v) && std::fabs(v) < 1e15) j = static_cast<long long>(v);
  return j.dump();
}
}  // namespace

namespace {
nlohmann::json check_type_and_range(const ParamSpec& spec, const nlohmann::json& value,
                                    const std::string& file, const std::string& pointer) {
  const std::string where = "parameter '" + spec.name + "': ";
  switch (spec.type) {
    case ParamType::Int: {
      if (!value.is_number_integer() &&
          !(value.is_number_float() && value.get<double>() == std::floor(value.get<double>())))
        throw InputError(file, pointer, where + "expected an integer, found " + describe(value));
      const double v = value.get<double>();
      if (v < spec.min || v > spec.max)
        throw InputError(file, pointer,
                         where + "expected an integer in [" + number(spec.min) + ", " +
                             number(spec.max) + "], found " + quoted_json(value));
      return static_cast<long long>(v);
    }
    case ParamType::Float: {
      if (!value.is_number())
        throw InputError(file, pointer, where + "expected a number, found " + describe(value));
      const double v = value.get<double>();
      if (!std::isfinite(v) || v < spec.min || v > spec.max)
        throw InputError(file, pointer,
                         where + "expected a number in [" + number(spec.min) + ", " +
                             number(spec.max) + "], found " + quoted_json(value));
      return v;
    }
    case ParamType::Bool:
      if (!value.is_boolean())
        throw InputError(file, pointer, where + "expected true or false, found " + describe(value));
      return value;
    case ParamType::String:
      if (!value.is_string())
        throw InputError(file, pointer, where + "expected a string, found " + describe(value));
      if (spec.is_path && value.get<std::string>().empty())
        throw InputError(file, pointer, where + "expected a file path, found \"\"");
      return value;
    case ParamType::Choice: {
      std::string list;
      for (const auto& c : spec.choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
      if (!value.is_string())
        throw InputError(file, pointer,
                         where + "expected one of " + list + ", found " + describe(value));
      for (const auto& c : spec.choices)
        if (c == value.get<std::string>()) return value;
      throw InputError(file, pointer,
                       where + "expected one of " + list + ", found " + quoted_json(value));
    }
  }
  return value;
}

}  // namespace

nlohmann::json check_param_value(const ParamSpec& spec, const nlohmann::json& value,
                                 const std::string& file, const std::string& pointer) {
  nlohmann::json v = check_type_and_range(spec, value, file, pointer);
  if (spec.rule) {
    const std::string expected = spec.rule(v);
    if (!expected.empty())
      throw InputError(
          file, pointer,
          "parameter '" + spec.name + "': expected " + expected + ", found " + quoted_json(value));
  }
  return v;
}

Params resolve_params(const std::vector<ParamSpec>& specs, const nlohmann::json& given,
                      const std::string& file, const std::string& pointer) {
  nlohmann::json out = nlohmann::json::object();
  if (!given.is_null() && !given.is_object())
    throw InputError(file, pointer, "expected an object of parameters, found " + describe(given));
  if (given.is_object()) {
    for (auto it = given.begin(); it != given.end(); ++it) {
      bool known = false;
      for (const auto& s : specs) known = known || s.name == it.key();
      if (!known) {
        std::string names;
        for (const auto& s : specs) names += (names.empty() ? "" : ", ") + s.name;
        throw InputError(file, pointer + "/" + it.key(),
                         "unknown parameter '" + it.key() +
                             "' (known: " + (names.empty() ? "none" : names) + ")");
      }
    }
  }
  for (const auto& s : specs) {
    if (given.is_object() && given.contains(s.name))
      out[s.name] = check_param_value(s, given.at(s.name), file, pointer + "/" + s.name);
    else if (s.is_path && s.default_value == "")
      throw InputError(file, pointer + "/" + s.name,
                       "parameter '" + s.name + "': expected a file path, found nothing");
    else
      out[s.name] = s.default_value;
  }
  return Params(std::move(out));
}

}  // namespace sb
