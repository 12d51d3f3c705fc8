#include "cli/new_technique.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/error.h"

namespace sb::cli {

using core::InputError;
using plugin::Registry;
using plugin::TechniqueInfo;

namespace {

namespace fs = std::filesystem;

// C++20's keywords and alternative tokens in lowercase: NAME becomes the
// namespace "NAME_plugin" (always fine) but also a CMake target and a
// project, and a reader would stumble over `class` or `and` as a name.
bool is_keyword(const std::string& name) {
  static const std::set<std::string> keywords = {"alignas",       "alignof",     "and",
                                                 "and_eq",        "asm",         "auto",
                                                 "bitand",        "bitor",       "bool",
                                                 "break",         "case",        "catch",
                                                 "char",          "char8_t",     "char16_t",
                                                 "char32_t",      "class",       "compl",
                                                 "concept",       "const",       "consteval",
                                                 "constexpr",     "constinit",   "const_cast",
                                                 "continue",      "co_await",    "co_return",
                                                 "co_yield",      "decltype",    "default",
                                                 "delete",        "do",          "double",
                                                 "dynamic_cast",  "else",        "enum",
                                                 "explicit",      "export",      "extern",
                                                 "false",         "float",       "for",
                                                 "friend",        "goto",        "if",
                                                 "inline",        "int",         "long",
                                                 "mutable",       "namespace",   "new",
                                                 "noexcept",      "not",         "not_eq",
                                                 "nullptr",       "operator",    "or",
                                                 "or_eq",         "private",     "protected",
                                                 "public",        "register",    "reinterpret_cast",
                                                 "requires",      "return",      "short",
                                                 "signed",        "sizeof",      "static",
                                                 "static_assert", "static_cast", "struct",
                                                 "switch",        "template",    "this",
                                                 "thread_local",  "throw",       "true",
                                                 "try",           "typedef",     "typeid",
                                                 "typename",      "union",       "unsigned",
                                                 "using",         "virtual",     "void",
                                                 "volatile",      "wchar_t",     "while",
                                                 "xor",           "xor_eq"};
  return keywords.count(name) > 0;
}

// Target names CMake refuses (policy CMP0037, an error from 3.0 on; the
// template's cmake_minimum_required sets it to NEW): its generators reserve
// these lowercase ones (CMake 3.25's cmGlobalGenerator::IsReservedTarget; the
// others there are upper case, which NAME cannot be), and "test", "package"
// and "package_source" once CTest or CPack is included (always before 3.11).
// NAME is the plugin's CMake target, so each of these made a project CMake
// refused at configure time ("The target name \"all\" is reserved").
bool is_cmake_reserved(const std::string& name) {
  static const std::set<std::string> reserved = {
      "all",        "clean",         "edit_cache", "help",    "install",
      "preinstall", "rebuild_cache", "test",       "package", "package_source"};
  return reserved.count(name) > 0;
}

std::string fill(std::string text, const std::map<std::string, std::string>& values) {
  for (const auto& [key, value] : values) {
    for (size_t at = text.find(key); at != std::string::npos;
         at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  }
  return text;
}

}  // namespace

std::string technique_name_problem(const std::string& name, const Registry& registry) {
  constexpr size_t kMaxLength = 48;
  const std::string expected =
      "expected a lowercase C identifier (a-z, 0-9 and '_', starting with a letter)";
  if (name.empty()) return "NAME is empty; " + expected;
  if (name.front() < 'a' || name.front() > 'z')
    return "NAME '" + name + "' does not start with a lowercase letter; " + expected;
  for (const char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) {
      std::string problem = "NAME '" + name + "' has the character '";
      problem += c;
      return problem.append("'; ").append(expected);
    }
  }
  // Job file names spell "__" otherwise (core/names.h), so they would lose
  // the name to a hash.
  if (name.find("__") != std::string::npos) return "NAME '" + name + "' has \"__\"; use one '_'";
  if (name.size() > kMaxLength)
    return "NAME '" + name + "' has " + std::to_string(name.size()) + " characters; at most " +
           std::to_string(kMaxLength);
  if (is_keyword(name)) return "NAME '" + name + "' is a C++ keyword";
  if (is_cmake_reserved(name))
    return "NAME '" + name +
           "' is a target name CMake reserves (policy CMP0037); the plugin's CMake target is "
           "NAME, so choose another name";
  if (const TechniqueInfo* t = registry.find(name))
    return "NAME '" + name + "' is a technique already (family " + t->family +
           "); choose another name";
  return "";
}

std::vector<std::string> write_technique_folder(const TechniqueTemplate& tmpl,
                                                const std::string& name,
                                                const std::map<std::string, std::string>& values,
                                                const std::string& folder) {
  std::error_code ec;
  if (fs::symlink_status(folder, ec).type() != fs::file_type::not_found)
    throw InputError(folder, "",
                     "exists already; new-technique writes a new folder and never overwrites "
                     "(choose another --dir, or remove it)");
  std::map<std::string, std::string> all = values;
  all["@NAME@"] = name;
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder, "", "cannot create the folder: " + ec.message());
  std::vector<std::string> written;
  for (const TemplateFile& f : tmpl.files) {
    const std::string path = (fs::path(folder) / fill(f.path, all)).string();
    std::ofstream out(path, std::ios::binary);
    out << fill(f.content, all);
    if (!out.flush()) throw InputError(path, "", "cannot write the file");
    written.push_back(path);
  }
  return written;
}

}  // namespace sb::cli
