#include "scenes/gltf_common.h"

#include <cmath>

#include "core/error.h"

namespace sb::gltf {

using core::InputError;

void ImportStep::fail(const std::string& where, const std::string& what) const {
  throw InputError(file_, where, what);
}

std::string str(uint64_t v) { return std::to_string(v); }
std::string quoted(const std::string& s) {
  std::string q = s.size() > 80 ? s.substr(0, 77) + "..." : s;
  return "'" + q + "'";
}
std::string named(const std::string& kind, const std::string& name, size_t index) {
  return name.empty() ? kind + " " + str(index)
                      : kind + " " + quoted(name) + " (" + str(index) + ")";
}
std::string describe(const json& v) {
  std::string d = v.dump();
  if (d.size() > 40) d = d.substr(0, 37) + "...";
  return std::string(v.type_name()) + " " + d;
}
std::string first_line(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  return l.empty() ? "unknown error" : l;
}

const tg::Value* member(const tg::Value& v, const char* key) {
  if (!v.IsObject() || !v.Has(key)) return nullptr;
  return &v.Get(key);
}
bool finite_number(const tg::Value* v, double& out) {
  if (v == nullptr || !v->IsNumber()) return false;
  out = v->GetNumberAsDouble();
  return std::isfinite(out);
}

}  // namespace sb::gltf
