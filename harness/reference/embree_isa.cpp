#include "reference/embree_isa.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace sb::reference {

namespace {

constexpr const char* kSyntax = "expected \"isa=NAME\" or \"max_isa=NAME\" with NAME one of ";

std::string isa_list() {
  std::string s;
  for (const std::string& isa : embree_isas()) s += (s.empty() ? "" : ", ") + isa;
  return s;
}

int isa_rank(const std::string& isa) {
  const auto& all = embree_isas();
  const auto it = std::find(all.begin(), all.end(), isa);
  return it == all.end() ? -1 : int(it - all.begin());
}

int best_rank() {
  // The extensions Embree's kernels for each ISA need (its getCPUFeatures).
  __builtin_cpu_init();
  int best = 0;  // sse2: every x86-64
  if (__builtin_cpu_supports("sse4.2")) best = 1;
  if (best == 1 && __builtin_cpu_supports("avx")) best = 2;
  if (best == 2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
      __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2"))
    best = 3;
  if (best == 3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl"))
    best = 4;
  return best;
}

struct Parsed {
  std::string key;  // "", "isa" or "max_isa"
  std::string isa;
};

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

Parsed parse(const std::string& config) {
  const std::string text = trim(config);
  if (text.empty()) return {};
  const size_t eq = text.find('=');
  const std::string key = trim(text.substr(0, eq));
  const std::string value = eq == std::string::npos ? "" : trim(text.substr(eq + 1));
  if (eq == std::string::npos || (key != "isa" && key != "max_isa"))
    throw std::invalid_argument("Embree device config \"" + config + "\": " + kSyntax + isa_list());
  std::string isa = value;
  std::transform(isa.begin(), isa.end(), isa.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (isa == "sse42") isa = "sse4.2";  // Embree takes both spellings
  if (isa_rank(isa) < 0)
    throw std::invalid_argument("Embree device config \"" + config + "\": unknown ISA \"" + value +
                                "\"; " + kSyntax + isa_list());
  return {key, isa};
}

}  // namespace

const std::vector<std::string>& embree_isas() {
  static const std::vector<std::string> kIsas = {"sse2", "sse4.2", "avx", "avx2", "avx512"};
  return kIsas;
}

std::string best_cpu_isa() { return embree_isas()[size_t(best_rank())]; }

bool cpu_supports_isa(const std::string& isa) {
  const int r = isa_rank(isa);
  return r >= 0 && r <= best_rank();
}

void check_embree_config(const std::string& config) { (void)parse(config); }

std::string resolve_isa(const std::string& config) {
  const Parsed p = parse(config);
  const int best = best_rank();
  if (p.key.empty()) return embree_isas()[size_t(best)];
  const int asked = isa_rank(p.isa);
  if (p.key == "max_isa") return embree_isas()[size_t(std::min(asked, best))];
  if (asked > best)
    throw UnsupportedIsa("Embree device config \"" + config + "\": this CPU supports at most " +
                         embree_isas()[size_t(best)]);
  return p.isa;
}

std::string default_embree_config() {
  const char* config = std::getenv("SHADOWBENCH_EMBREE_CONFIG");
  if (config != nullptr && *config != '\0') return config;
  const char* isa = std::getenv("SHADOWBENCH_EMBREE_ISA");
  if (isa != nullptr && *isa != '\0') return std::string("isa=") + isa;
  return "";
}

}  // namespace sb::reference
