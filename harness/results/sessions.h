#pragma once
// Which `run` sessions timed a set of records (record/session_record.h). A
// run folder resumed after a change keeps the earlier session's records
// beside the new one's, and times from two sessions are not comparable (the
// machine's load, its clocks, the processes beside it differ): every report
// over such records says so, in a banner above its tables and a "session"
// column of letters, one per session. `compare` sets two runs side by side
// by design, and does neither.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "record/job_record.h"
#include "results/banner.h"
#include "results/report_columns.h"

namespace sb::results {

class Sessions {
 public:
  // The sessions of the ok records (the others have no times), told apart
  // by id, in order of first appearance; records without a session count
  // as one session of their own (record::kUnrecordedSession).
  explicit Sessions(const std::vector<record::JobRecord>& records);

  size_t count() const { return sessions_.size(); }
  bool mixed() const { return count() > 1; }
  // "A" for the first session, "B", ..., "Z", "AA", ...; "" for a record
  // that is not ok.
  std::string letter(const record::JobRecord& r) const;
  // "Mixed sessions": "these N jobs were measured in K sessions: ...; times
  // from different sessions are not comparable", and a line per session
  // (its letter, id, start, host, load average and job count). None
  // unless mixed.
  std::optional<Banner> banner() const;
  // `columns` with the "session" column (each ok record's letter) after
  // "technique", or first without one, when mixed; as they are otherwise.
  // The pointers are valid while this object is.
  std::vector<const ReportColumn*> marked(std::vector<const ReportColumn*> columns) const;

 private:
  struct Session {
    std::string id;
    std::optional<record::SessionRecord> record;  // none: unrecorded
    int jobs = 0;
  };
  std::vector<Session> sessions_;
  std::shared_ptr<std::map<std::string, std::string>> letters_;  // by session id
  int jobs_ = 0;
  ReportColumn column_;
};

}  // namespace sb::results
