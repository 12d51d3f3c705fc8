#include "config/sweeps.h"

#include <algorithm>

#include "core/error.h"

namespace sb::config {

using core::InputError;
using core::Params;
using core::ParamSpec;
using core::pointer_token;
using core::resolve_params;

using json = nlohmann::json;

namespace {

std::string value_label(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

uint64_t saturating_mul(uint64_t a, uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

}  // namespace

std::string variant_name(const std::string& base, const std::vector<ParamSpec>& specs,
                         const json& given) {
  std::string suffix;
  for (const auto& s : specs)
    if (given.contains(s.name))
      suffix += (suffix.empty() ? "" : ",") + s.name + "=" + value_label(given.at(s.name));
  return suffix.empty() ? base : base + "/" + suffix;
}

// How many variants an entry's parameters sweep to (the product of its
// lists' lengths), saturating instead of overflowing; malformed parameters
// count as one (expand_sweeps reports them).
uint64_t sweep_count(const json& params) {
  uint64_t n = 1;
  if (!params.is_object()) return n;
  for (const auto& v : params) {
    const uint64_t k = v.is_array() ? std::max<uint64_t>(v.size(), 1) : 1;
    n = n > UINT64_MAX / k ? UINT64_MAX : n * k;
  }
  return n;
}

// Jobs = scene variants × technique variants × resolutions, from the lists'
// lengths alone: a sweep too big to run is refused before it is expanded.
void check_job_count(const ConfigReader& r, const json& doc, const ExperimentLimits& limits) {
  uint64_t scenes = 0, techniques = 0, resolutions = 1;
  std::string biggest;  // the entry with the most variants, for the message
  uint64_t biggest_n = 0;
  const auto count = [&](const char* list, uint64_t& total) {
    if (!doc.contains(list) || !doc[list].is_array()) return;
    for (size_t i = 0; i < doc[list].size(); ++i) {
      const json& entry = doc[list][i];
      const uint64_t n =
          entry.is_object() && entry.contains("params") ? sweep_count(entry["params"]) : 1;
      total = total > UINT64_MAX - n ? UINT64_MAX : total + n;
      if (n > biggest_n) {
        biggest_n = n;
        biggest = std::string("/") + list + "/" + std::to_string(i) + "/params";
      }
    }
  };
  count("scenes", scenes);
  count("techniques", techniques);
  if (doc.contains("resolutions") && doc["resolutions"].is_array())
    resolutions = std::max<uint64_t>(doc["resolutions"].size(), 1);
  const uint64_t jobs = saturating_mul(saturating_mul(scenes, techniques), resolutions);
  if (jobs > limits.max_jobs)
    r.fail(biggest.empty() ? "/" : biggest,
           "the experiment has " +
               (jobs == UINT64_MAX ? std::string("more than 2^64") : std::to_string(jobs)) +
               " jobs (" + std::to_string(scenes) + " scene variants × " +
               std::to_string(techniques) + " technique variants × " + std::to_string(resolutions) +
               " resolutions), over the limit of " + std::to_string(limits.max_jobs) +
               "; raise it with --max-jobs");
}

std::vector<json> expand_sweeps(const json& params, const std::string& file,
                                const std::string& pointer) {
  std::vector<json> out{json::object()};
  if (params.is_null()) return out;
  ConfigReader(file).object(params, pointer, "parameters");
  // Counted before anything is expanded.
  if (sweep_count(params) > 100000)
    throw InputError(file, pointer, "the sweep expands to more than 100000 variants");
  for (auto it = params.begin(); it != params.end(); ++it) {
    std::vector<json> values;
    if (it.value().is_array()) {
      if (it.value().empty())
        throw InputError(file, pointer + "/" + it.key(),
                         "expected a non-empty list to sweep, found []");
      for (const auto& v : it.value()) values.push_back(v);
    } else {
      values.push_back(it.value());
    }
    std::vector<json> next;
    for (const auto& partial : out)
      for (const auto& v : values) {
        json p = partial;
        p[it.key()] = v;
        next.push_back(std::move(p));
      }
    out = std::move(next);
  }
  return out;
}

std::string swept_pointer(const json& given, const json& combo, const std::string& pointer,
                          const std::string& key) {
  const std::string member = pointer + "/" + pointer_token(key);
  if (!given.is_object() || !given.contains(key) || !given[key].is_array() || !combo.contains(key))
    return member;
  const json& list = given[key];
  for (size_t i = 0; i < list.size(); ++i)
    if (list[i] == combo[key]) return member + "/" + std::to_string(i);
  return member;
}

Params resolve_sweep_combo(const std::vector<ParamSpec>& specs, const json& given,
                           const json& combo, const std::string& file, const std::string& pointer) {
  try {
    return resolve_params(specs, combo, file, pointer);
  } catch (const InputError& e) {
    // A known parameter's bad value is one element of its list; an unknown
    // parameter is wrong as a key, whatever its values.
    const auto known = [&specs](const std::string& key) {
      return std::any_of(specs.begin(), specs.end(),
                         [&key](const ParamSpec& s) { return s.name == key; });
    };
    if (given.is_object())
      for (auto it = given.begin(); it != given.end(); ++it)
        if (known(it.key()) && e.where() == pointer + "/" + pointer_token(it.key()))
          throw InputError(e.file(), swept_pointer(given, combo, pointer, it.key()), e.problem(),
                           e.position());
    throw;
  }
}

}  // namespace sb::config
