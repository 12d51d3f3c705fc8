#include "record/host_record.h"

#include <cctype>
#include <string_view>

#include "core/hash.h"
#include "record/record_json.h"

namespace sb::record {

using core::Hasher;

using json = nlohmann::json;

namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The version that follows `word ` in `text` ("Mesa 22.3.6-devel (git-1)" →
// "22.3.6-devel"): starts with a digit, ends at a space, comma or parenthesis.
std::optional<std::string> version_after(std::string_view text, std::string_view word) {
  for (size_t at = text.find(word); at != std::string_view::npos; at = text.find(word, at + 1)) {
    // A whole word: not "XMesa", and followed by one space then a digit.
    if (at > 0 && std::isalnum(static_cast<unsigned char>(text[at - 1]))) continue;
    size_t i = at + word.size();
    if (i + 1 >= text.size() || text[i] != ' ' || !is_digit(text[i + 1])) continue;
    ++i;
    size_t end = i;
    while (end < text.size() && text[end] != ' ' && text[end] != ',' && text[end] != '(' &&
           text[end] != ')')
      ++end;
    return std::string(text.substr(i, end - i));
  }
  return std::nullopt;
}

// llvmpipe's "(LLVM 15.0.6, 256 bits)": the number before " bits)".
std::optional<int> vector_bits(std::string_view renderer) {
  if (renderer.rfind("llvmpipe", 0) != 0) return std::nullopt;
  const size_t at = renderer.find(" bits)");
  if (at == std::string_view::npos) return std::nullopt;
  size_t start = at;
  while (start > 0 && is_digit(renderer[start - 1])) --start;
  if (start == at || at - start > 5) return std::nullopt;
  return std::stoi(std::string(renderer.substr(start, at - start)));
}

std::string fingerprint_of(std::string_view what,
                           const std::vector<std::pair<std::string, std::string>>& fields) {
  Hasher h;
  h.add(what);
  for (const auto& [name, value] : fields) h.add(name).add(value);
  return h.hex();
}

// A value as JSON text; "" (unset, unknown) as (none).
std::string as_json_or_none(const std::string& s) {
  return s.empty() ? "(none)" : json(s).dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

GlStack parse_gl_stack(const std::string& gl_renderer, const std::string& gl_version) {
  GlStack s;
  s.mesa_version = version_after(gl_version, "Mesa");
  s.llvm_version = version_after(gl_renderer, "LLVM");
  s.vector_bits = vector_bits(gl_renderer);
  return s;
}

json HostRecord::to_json() const { return write_record(*this); }
HostRecord HostRecord::from_json(const Fields& f) { return read_record<HostRecord>(f); }
json BuildRecord::to_json() const { return write_record(*this); }
BuildRecord BuildRecord::from_json(const Fields& f) { return read_record<BuildRecord>(f); }

std::vector<std::pair<std::string, std::string>> host_fingerprint_fields(
    const HostRecord& host, const std::string& gl_renderer, const std::string& gl_version) {
  std::vector<std::pair<std::string, std::string>> out;
  std::string isa;
  if (host.cpu)
    for (const auto& feature : host.cpu->isa) isa += (isa.empty() ? "" : " ") + feature;
  out.emplace_back("cpu.model", host.cpu ? host.cpu->model : "");
  out.emplace_back("cpu.isa", isa);
  out.emplace_back("cpu.logical_cores", host.cpu ? std::to_string(host.cpu->logical_cores) : "");
  out.emplace_back("gl_renderer", gl_renderer);
  out.emplace_back("gl_version", gl_version);
  for (const char* name : kTimingEnvironment) {
    const auto it = host.env.find(name);
    out.emplace_back(std::string("env.") + name, it == host.env.end() ? "" : it->second);
  }
  out.emplace_back("os", host.os.value_or(""));
  return out;
}

std::string host_fingerprint(const HostRecord& host, const std::string& gl_renderer,
                             const std::string& gl_version) {
  return fingerprint_of("shadowbench host fingerprint 1",
                        host_fingerprint_fields(host, gl_renderer, gl_version));
}

std::vector<std::pair<std::string, std::string>> build_fingerprint_fields(const BuildRecord& b) {
  return {{"version", b.version},
          {"compiler", b.compiler.value_or("")},
          {"build_type", b.build_type.value_or("")},
          {"cxx_flags", b.cxx_flags.value_or("")}};
}

std::string build_fingerprint(const BuildRecord& b) {
  return fingerprint_of("shadowbench build fingerprint 1", build_fingerprint_fields(b));
}

std::vector<std::string> field_differences(
    const std::vector<std::pair<std::string, std::string>>& a,
    const std::vector<std::pair<std::string, std::string>>& b) {
  std::vector<std::string> out;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    if (a[i].second != b[i].second)
      out.push_back(a[i].first + ": " + as_json_or_none(a[i].second) + " vs " +
                    as_json_or_none(b[i].second));
  return out;
}

}  // namespace sb::record
