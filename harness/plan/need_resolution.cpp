#include "plan/need_resolution.h"

#include <set>
#include <stdexcept>

#include "scenes/need_providers.h"

namespace sb::plan {

using core::Scene;
using plugin::NeedProvider;
using plugin::Registry;
using plugin::TechniqueInfo;

const NeedProvider* find_need_provider(const std::string& name, const Registry* plugins) {
  const NeedProvider* from_plugin = plugins != nullptr ? plugins->find_provider(name) : nullptr;
  for (const auto& p : builtin_need_providers())
    if (p.name == name) {
      // A plugin must not quietly change what a harness need means for
      // every other technique of the run.
      if (from_plugin != nullptr)
        throw std::logic_error("a plugin provides the need '" + name +
                               "', which the harness provides already; give the plugin's need a "
                               "name of its own");
      return &p;
    }
  return from_plugin;
}

namespace {

class Resolver {
 public:
  Resolver(const Scene& scene, const Registry* plugins, ResolvedNeeds& out)
      : scene_(scene), plugins_(plugins), out_(out) {}

  // The needs of `names` and everything they require, dependencies first;
  // "" when all have providers, else the first name without one.
  std::string closure(const std::vector<std::string>& names,
                      std::vector<const NeedProvider*>& order) const {
    std::set<std::string> visiting, done;
    for (const auto& n : names) {
      std::string missing = visit(n, visiting, done, order);
      if (!missing.empty()) return missing;
    }
    return "";
  }

  void derive(const NeedProvider& p) {
    if (!derived_.insert(p.name).second) return;
    if (p.derive) p.derive(scene_, out_.data, out_.log);
  }

 private:
  std::string visit(const std::string& name, std::set<std::string>& visiting,
                    std::set<std::string>& done, std::vector<const NeedProvider*>& order) const {
    if (done.count(name)) return "";
    if (!visiting.insert(name).second)
      throw std::logic_error("needs require each other in a cycle through '" + name + "'");
    const NeedProvider* p = find_need_provider(name, plugins_);
    if (p == nullptr) return name;
    for (const auto& r : p->requires_needs) {
      std::string missing = visit(r, visiting, done, order);
      if (!missing.empty()) return missing;
    }
    visiting.erase(name);
    done.insert(name);
    order.push_back(p);
    return "";
  }

  const Scene& scene_;
  const Registry* plugins_;
  ResolvedNeeds& out_;
  std::set<std::string> derived_;
};

}  // namespace

ResolvedNeeds resolve_needs(const Scene& scene, const std::vector<const TechniqueInfo*>& techniques,
                            const Registry* plugins, Derive derive,
                            const plugin::DerivedData* decided) {
  ResolvedNeeds out;
  if (decided != nullptr) out.data = *decided;
  Resolver resolver(scene, plugins, out);
  std::vector<std::vector<const NeedProvider*>> per_technique(techniques.size());
  out.skip_reason.assign(techniques.size(), "");
  out.needs.resize(techniques.size());
  for (size_t t = 0; t < techniques.size(); ++t) {
    std::vector<std::string> names = techniques[t]->needs.names;
    if (!techniques[t]->needs.has(plugin::need::kSunLight) &&
        !techniques[t]->needs.has(plugin::need::kSunOrLocalLight))
      names.emplace_back(plugin::need::kLocalLight);
    const std::string missing = resolver.closure(names, per_technique[t]);
    if (!missing.empty())
      out.skip_reason[t] =
          techniques[t]->name + " needs '" + missing + "', which no loaded plugin provides";
    else
      for (const NeedProvider* p : per_technique[t]) out.needs[t].push_back(p->name);
  }
  // Plan needs of every technique (even those about to be skipped: their
  // reasons come from these), in the techniques' order.
  for (size_t t = 0; t < techniques.size() && decided == nullptr; ++t)
    for (const NeedProvider* p : per_technique[t])
      if (p->when == NeedProvider::When::Plan) resolver.derive(*p);
  for (size_t t = 0; t < techniques.size(); ++t) {
    if (!out.skip_reason[t].empty()) continue;
    for (const NeedProvider* p : per_technique[t]) {
      if (!p->unmet) continue;
      if (p->when != NeedProvider::When::Plan)
        throw std::logic_error("need '" + p->name +
                               "' checks the scene but is not a Plan need: only Plan needs, "
                               "computed before the decisions, may skip a job");
      const std::string why = p->unmet(scene, out.data);
      if (!why.empty()) {
        out.skip_reason[t] = techniques[t]->name + " " + why;
        break;
      }
    }
  }
  // Run needs of the techniques that will run, once each.
  std::set<std::string> seen;
  for (size_t t = 0; t < techniques.size(); ++t) {
    if (!out.skip_reason[t].empty()) continue;
    for (const NeedProvider* p : per_technique[t]) {
      if (!seen.insert(p->name).second) continue;
      if (p->when == NeedProvider::When::Run) {
        if (derive == Derive::All) {
          resolver.derive(*p);
        } else {
          out.log.push_back(p->summary + " (built when run)");
          ++out.deferred;
        }
      }
      if (p->upload) out.uploads.push_back(p);
    }
  }
  return out;
}

}  // namespace sb::plan
