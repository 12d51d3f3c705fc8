#include "record/job_record.h"

#include <utility>

#include "core/install_layout.h"
#include "record/record_json.h"

namespace sb::record {

using json = nlohmann::json;

namespace {

void check_schema_version(const json& j) {
  const Fields f(j, "");
  if (!f.has("schema_version"))
    f.fail("schema_version", "missing: this is not a shadowbench job record");
  const json& v = j.at("schema_version");
  if (!v.is_number_integer() || v.get<std::int64_t>() != kRecordSchemaVersion)
    f.fail("schema_version", "the record has schema_version " + v.dump() +
                                 "; this shadowbench reads schema_version " +
                                 std::to_string(kRecordSchemaVersion) + " (" +
                                 core::doc_path("results.md") + ")");
}

}  // namespace

JobStatus status_from(const Fields& f) {
  const std::string s = f.choice("status", {to_string(JobStatus::Ok), to_string(JobStatus::Skipped),
                                            to_string(JobStatus::Failed)});
  for (const JobStatus st : {JobStatus::Ok, JobStatus::Skipped})
    if (s == to_string(st)) return st;
  return JobStatus::Failed;
}

const char* to_string(JobStatus s) {
  switch (s) {
    case JobStatus::Ok:
      return "ok";
    case JobStatus::Skipped:
      return "skipped";
    case JobStatus::Failed:
      break;
  }
  return "failed";
}

bool ImagesRecord::empty() const { return write_record(*this).empty(); }

namespace {

// Takes each member `other` has: a path it names, a mask per region.
class TakeImages {
 public:
  TakeImages(ImagesRecord& to, const ImagesRecord& from) : to_(to), from_(from) {}
  template <class M>
  void field(const char* /*key*/, M ImagesRecord::*member, const FieldInfo& /*info*/ = {}) {
    if constexpr (describe_detail::Optional<M>::value) {
      if (from_.*member) to_.*member = from_.*member;
    } else {
      for (const auto& [region, path] : from_.*member) (to_.*member)[region] = path;
    }
  }

 private:
  ImagesRecord& to_;
  const ImagesRecord& from_;
};

}  // namespace

void ImagesRecord::add(const ImagesRecord& other) {
  TakeImages take(*this, other);
  describe(take);
}

json JobRecord::to_json() const { return write_record(*this); }

JobRecord JobRecord::from_json(const json& j) {
  check_schema_version(j);
  JobRecord r = read_record<JobRecord>(Fields(j, ""));
  r.schema_version = kRecordSchemaVersion;
  r.set_aside_failed_measurements();
  return r;
}

namespace {

// Moves `from` into `to` unless `to` has a value already; `from` is left empty.
template <class T>
void set_aside(std::optional<T>& from, std::optional<T>& to) {
  std::optional<T> taken = std::exchange(from, std::nullopt);
  if (!to) to = std::move(taken);
}

}  // namespace

void JobRecord::set_aside_failed_measurements() {
  if (status != JobStatus::Failed) return;
  PartialRecord p = partial.value_or(PartialRecord{});
  set_aside(timing, p.timing);
  set_aside(technique.gpu_bytes, p.gpu_bytes);
  set_aside(technique.gpu_own_bytes, p.gpu_own_bytes);
  set_aside(technique.gpu_need_bytes, p.gpu_need_bytes);
  set_aside(metrics, p.metrics);
  set_aside(second_reference, p.second_reference);
  set_aside(classes, p.classes);
  if (p.empty())
    partial.reset();
  else
    partial = std::move(p);
}

std::optional<double> JobRecord::metric(const MetricPath& path) const {
  if (!metrics) return std::nullopt;
  return path.of(*metrics);
}

}  // namespace sb::record
