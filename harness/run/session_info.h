#pragma once
// The session every record of one `run` process names (record/session_record.h):
// a random id, when the process started, the host name, and the 1-minute
// load average then, so that a report can tell records of different
// processes apart (results/sessions.h).
#include <optional>
#include <string>
#include <string_view>

#include "record/session_record.h"

namespace sb::run {

// A new session, now: 16 random hex digits (std::random_device), the UTC
// time, gethostname() and /proc/loadavg (0 where it cannot be read).
record::SessionRecord start_session();

// The 1-minute load average of a /proc/loadavg text ("0.52 0.58 0.59 1/189
// 4242"): its first number; nullopt when it does not start with one.
std::optional<double> loadavg_one_minute(std::string_view loadavg);

}  // namespace sb::run
