#include "plugin/derived_data.h"

#include <cxxabi.h>

#include <cstdlib>
#include <stdexcept>

namespace sb::plugin {
namespace {

std::string readable_type(const std::string& mangled) {
  int status = 0;
  char* name = abi::__cxa_demangle(mangled.c_str(), nullptr, nullptr, &status);
  std::string out = status == 0 && name != nullptr ? name : mangled;
  std::free(name);  // NOLINT(cppcoreguidelines-no-malloc): __cxa_demangle's contract
  return out;
}

}  // namespace

std::vector<std::string> DerivedData::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : entries_) out.push_back(name);
  return out;
}

void DerivedData::merge(const DerivedData& other) {
  for (const auto& [name, entry] : other.entries_) entries_[name] = entry;
}

void DerivedData::check_type(const std::string& name, const std::string& held,
                             const std::string& wanted) {
  if (held != wanted)
    throw std::logic_error("need '" + name + "' holds " + readable_type(held) + ", read as " +
                           readable_type(wanted));
}

void DerivedData::throw_absent(const std::string& name) {
  throw std::logic_error("need '" + name +
                         "' was not derived for this scene: declare it in the technique's Needs");
}

}  // namespace sb::plugin
