#include "scenes/gltf_common.h"

#include <cmath>

#include "core/bounded_text.h"
#include "core/error.h"

namespace sb::gltf {

using core::InputError;

void ImportStep::fail(const std::string& where, const std::string& what) const {
  throw InputError(file_, where, what);
}

std::string str(uint64_t v) { return std::to_string(v); }
std::string quoted(const std::string& s) { return core::quoted_text(s); }
std::string named(const std::string& kind, const std::string& name, size_t index) {
  return name.empty() ? kind + " " + str(index)
                      : kind + " " + quoted(name) + " (" + str(index) + ")";
}
std::string describe(const json& v) {
  return std::string(v.type_name()) + " " + core::bounded_text(v.dump(), 40);
}
std::string first_line(const std::string& s) {
  const std::string_view l = std::string_view(s).substr(0, s.find('\n'));
  return l.empty() ? "unknown error" : core::bounded_text(l, core::kQuoteChars);
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
