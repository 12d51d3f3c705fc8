#include "record/host_record.h"

#include <cctype>
#include <string_view>

#include "core/hash.h"

namespace sb {

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

// The optional string members of a record type, by key, in one list for
// both directions.
template <class R>
struct OptionalString {
  const char* key;
  std::optional<std::string> R::*member;
};

const OptionalString<HostRecord> kHostStrings[] = {
    {"lp_num_threads", &HostRecord::lp_num_threads},
    {"name", &HostRecord::name},
    {"os", &HostRecord::os},
    {"kernel", &HostRecord::kernel},
    {"cpu_governor", &HostRecord::cpu_governor},
    {"embree_isa", &HostRecord::embree_isa},
    {"fingerprint", &HostRecord::fingerprint},
};
const OptionalString<BuildRecord> kBuildStrings[] = {
    {"compiler", &BuildRecord::compiler},
    {"build_type", &BuildRecord::build_type},
    {"cxx_flags", &BuildRecord::cxx_flags},
    {"fingerprint", &BuildRecord::fingerprint},
    {"driver_sha256", &BuildRecord::driver_sha256},
    {"core_sha256", &BuildRecord::core_sha256},
    {"plugin_api_sha256", &BuildRecord::plugin_api_sha256},
};
const OptionalString<GlStack> kGlStackStrings[] = {
    {"mesa_version", &GlStack::mesa_version},
    {"llvm_version", &GlStack::llvm_version},
};

template <class R, size_t N>
void put_strings(json& j, const R& r, const OptionalString<R> (&members)[N]) {
  for (const auto& m : members)
    if (const auto& v = r.*m.member) j[m.key] = *v;
}

template <class R, size_t N>
void read_strings(const Fields& f, R& r, const OptionalString<R> (&members)[N]) {
  for (const auto& m : members) r.*m.member = f.find<std::string>(m.key);
}

std::string fingerprint_of(std::string_view what,
                           const std::vector<std::pair<std::string, std::string>>& fields) {
  Hasher h;
  h.add(what);
  for (const auto& [name, value] : fields) h.add(name).add(value);
  return h.hex();
}

// A value as JSON text; "" (unset, unknown) as (none).
std::string quoted(const std::string& s) {
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

json HostRecord::to_json() const {
  json h = {{"hardware_threads", hardware_threads}};
  put_strings(h, *this, kHostStrings);
  if (cpu)
    h["cpu"] = {{"model", cpu->model}, {"isa", cpu->isa}, {"logical_cores", cpu->logical_cores}};
  if (gl_stack) {
    json g = json::object();
    put_strings(g, *gl_stack, kGlStackStrings);
    if (gl_stack->vector_bits) g["vector_bits"] = *gl_stack->vector_bits;
    h["gl_stack"] = g;
  }
  h["env"] = env;  // {} when none is set
  return h;
}

HostRecord HostRecord::from_json(const Fields& f) {
  HostRecord h;
  h.hardware_threads = f.get<std::int64_t>("hardware_threads");
  read_strings(f, h, kHostStrings);
  if (const auto c = f.find_object("cpu")) {
    CpuRecord cpu;
    cpu.model = c->get<std::string>("model");
    cpu.isa = c->get<std::vector<std::string>>("isa");
    cpu.logical_cores = c->get<std::int64_t>("logical_cores");
    h.cpu = std::move(cpu);
  }
  if (const auto g = f.find_object("gl_stack")) {
    GlStack s;
    read_strings(*g, s, kGlStackStrings);
    s.vector_bits = g->find<int>("vector_bits");
    h.gl_stack = s;
  }
  if (const auto e = f.find_object("env"))
    for (const auto& key : e->keys()) h.env[key] = e->get<std::string>(key);
  return h;
}

json BuildRecord::to_json() const {
  json b = {{"version", version}};
  put_strings(b, *this, kBuildStrings);
  return b;
}

BuildRecord BuildRecord::from_json(const Fields& f) {
  BuildRecord b;
  b.version = f.get<std::string>("version");
  read_strings(f, b, kBuildStrings);
  return b;
}

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
      out.push_back(a[i].first + ": " + quoted(a[i].second) + " vs " + quoted(b[i].second));
  return out;
}

}  // namespace sb
