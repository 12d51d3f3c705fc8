#include "results/reference_identity.h"

#include <charconv>

namespace sb::results {

using record::ReferenceRecord;

namespace {

// The shortest text that reads back as the same double: two settings that
// differ never print alike.
std::string exact_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return {buf, r.ptr};
}

}  // namespace

std::vector<std::pair<std::string, std::string>> reference_identity_fields(
    const std::optional<ReferenceRecord>& reference) {
  std::vector<std::pair<std::string, std::string>> f = {{"method", ""},
                                                        {"spp", ""},
                                                        {"seed", ""},
                                                        {"embree_isa", ""},
                                                        {"adaptive.pilot_spp", ""},
                                                        {"adaptive.target_std_error", ""},
                                                        {"cache_key", ""}};
  if (!reference) return f;
  const ReferenceRecord& r = *reference;
  f[0].second = r.method;
  f[1].second = std::to_string(r.spp);
  f[2].second = std::to_string(r.seed);
  f[3].second = r.embree_isa;
  if (r.adaptive) {
    f[4].second = std::to_string(r.adaptive->pilot_spp);
    f[5].second = exact_text(r.adaptive->target_std_error);
  }
  f[6].second = r.cache_key;
  return f;
}

}  // namespace sb::results
