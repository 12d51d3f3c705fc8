#include "results/sessions.h"

#include <algorithm>
#include <utility>

#include "core/format_number.h"

namespace sb::results {

using record::JobRecord;
using record::JobStatus;

namespace {

std::string session_id(const JobRecord& r) {
  return r.session ? r.session->id : std::string(record::kUnrecordedSession);
}

// 0 → "A", 25 → "Z", 26 → "AA": spreadsheet columns' letters.
std::string letter_of(size_t index) {
  std::string out;
  for (size_t n = index + 1; n > 0; n = (n - 1) / 26)
    out.insert(out.begin(), char('A' + (n - 1) % 26));
  return out;
}

std::string jobs_text(int n) { return std::to_string(n) + (n == 1 ? " job" : " jobs"); }

}  // namespace

Sessions::Sessions(const std::vector<JobRecord>& records)
    : letters_(std::make_shared<std::map<std::string, std::string>>()) {
  for (const JobRecord& r : records) {
    if (r.status != JobStatus::Ok) continue;  // no times to mix
    ++jobs_;
    const std::string id = session_id(r);
    auto it = std::find_if(sessions_.begin(), sessions_.end(),
                           [&](const Session& s) { return s.id == id; });
    if (it == sessions_.end()) {
      (*letters_)[id] = letter_of(sessions_.size());
      sessions_.push_back({id, r.session, 0});
      it = sessions_.end() - 1;
    }
    ++it->jobs;
  }
  column_.name = column_.header = column_.label = "session";
  column_.text = [letters = letters_](const JobRecord& r) -> std::string {
    if (r.status != JobStatus::Ok) return "";
    const auto it = letters->find(session_id(r));
    return it == letters->end() ? "" : it->second;
  };
}

std::string Sessions::letter(const JobRecord& r) const { return column_.text(r); }

std::optional<Banner> Sessions::banner() const {
  if (!mixed()) return std::nullopt;
  Banner b;
  b.title = "Mixed sessions";
  b.text = "these " + jobs_text(jobs_) + " were measured in " + std::to_string(count()) +
           " sessions (the session column's letters); times from different sessions are not "
           "comparable (`run --retime` times a run folder's kept jobs again in one session):";
  for (const Session& s : sessions_) {
    std::string item = letter_of(b.items.size()) + ": ";
    if (s.record)
      item += "session " + s.id + ", started " + s.record->started + " on " +
              (s.record->host.empty() ? std::string("?") : s.record->host) + ", load average " +
              core::format_number("%.2f", s.record->load_average);
    else
      item += "no session recorded (records written before sessions)";
    b.items.push_back(item + ": " + jobs_text(s.jobs));
  }
  return b;
}

std::vector<const ReportColumn*> Sessions::marked(std::vector<const ReportColumn*> columns) const {
  if (!mixed()) return columns;
  auto at = std::find_if(columns.begin(), columns.end(),
                         [](const ReportColumn* c) { return std::string(c->name) == "technique"; });
  columns.insert(at == columns.end() ? columns.begin() : at + 1, &column_);
  return columns;
}

}  // namespace sb::results
