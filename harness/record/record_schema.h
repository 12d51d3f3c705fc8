#pragma once
// The job record's schema, made from the record structs' descriptions
// (record/describe.h): the Markdown tables docs/results.md holds, which
// `shadowbench list --record-schema` prints and a test holds the file to,
// and the JSON pointers a record may have, which a test holds a written
// record to. So the documentation says what the code writes.
#include <string>
#include <vector>

namespace sb::record {

// One table per record struct, in the order a record holds them: each
// member's key, type, unit, when it is present and what it means.
std::string record_schema_markdown();

struct RecordPointers {
  // Every member a record may have, as a JSON pointer where "*" stands for
  // any name (a map's: "/timing/shared/*/median_ms").
  std::vector<std::string> members;
  // Those whose value is kept as it is, not described member by member
  // (a scene's params, the job's spec, max_pixel).
  std::vector<std::string> opaque;
};
RecordPointers record_pointers();

// The same for a run folder's plan.json (record/plan_record.h): the tables
// `shadowbench list --plan-schema` prints, and its members' pointers.
std::string plan_schema_markdown();
RecordPointers plan_pointers();

// Whether `pointer` ("/timing/shared/gbuffer") is `pattern`
// ("/timing/shared/*"), token by token.
bool pointer_matches(const std::string& pattern, const std::string& pointer);

}  // namespace sb::record
