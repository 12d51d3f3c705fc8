#pragma once
// record["session"]: the `run` process that timed a job (docs/results.md,
// "Sessions"). Frame times are comparable only within one session: a
// resumed run keeps the earlier session's records beside its own, and the
// machine's load, its clocks and the other processes on it change between
// the two. Reports say when their records come from several sessions
// (results/sessions.h); `run --retime` times kept jobs again in one session.
// Absent from records older than sessions, which read as of no session.
#include <optional>
#include <string>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

struct SessionRecord {
  static constexpr RecordDoc kSchema{
      "SessionRecord",
      "the `run` process that timed the job, with its children (\"Sessions\" below); absent "
      "from older records"};

  std::string id;           // 16 hex digits, random per `run` process
  std::string started;      // UTC ISO 8601: when that process started
  std::string host;         // the host name
  double load_average = 0;  // /proc/loadavg's 1-minute figure as it started
  // A record that `run --retime` timed again: the session whose metrics,
  // images and reference it keeps ("unrecorded" when that record had none).
  std::optional<std::string> retimed_from;

  // What a run folder from elsewhere may hold is what a run writes: an id
  // of 16 hex digits, a short time stamp, a host name of printable ASCII
  // within a host name's 255 bytes, a finite load; the reports print them.
  static void check(const SessionRecord& s, const Fields& f);

  template <class V>
  static void describe(V& v) {
    using S = SessionRecord;
    v.field("id", &S::id,
            {"",
             "16 hex digits drawn at random when the `run` process starts (its forked children "
             "share it): equal ids, one session"});
    v.field("started", &S::started, {"", "UTC ISO 8601: when that process started"});
    v.field("host", &S::host, {"", "the host name"});
    v.field("load_average", &S::load_average,
            {"", "`/proc/loadavg`'s 1-minute load average as the session started"});
    v.field("retimed_from", &S::retimed_from,
            {"",
             "with `run --retime`: the id of the session whose metrics, images and reference "
             "the record keeps (`unrecorded` when that record had no session); its timing is "
             "this session's"});
  }
};

// The id a record without a session is counted under ("unrecorded").
inline constexpr const char* kUnrecordedSession = "unrecorded";

}  // namespace sb::record
