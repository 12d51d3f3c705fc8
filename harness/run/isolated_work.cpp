#include "run/isolated_work.h"

#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <optional>
#include <set>
#include <stdexcept>

#include "core/bounded_text.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/names.h"
#include "run/child_process.h"
#include "run/io_trace.h"
#include "run/phase_board.h"
#include "store/results_store.h"

namespace sb::run {

using config::Experiment;
using config::Resolution;
using config::SceneVariant;
using core::format_number;
using plan::PlannedJob;
using record::JobRecord;
using record::JobStatus;
using store::json_text;

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

constexpr size_t kStderrTail = 20;  // lines kept for a failed record
constexpr int kExitContextFailed = 71;

// The parent's answer to "await": it has done all that the child's events
// so far asked.
constexpr const char* kHeard = "heard\n";

// The child's side: every event is one JSON line up the pipe; the parent
// answers "await" on `reply_fd`.
class PipeEvents final : public RunEvents {
 public:
  PipeEvents(int fd, int reply_fd, PhaseBoard& phases)
      : fd_(fd), reply_fd_(reply_fd), phases_(phases) {}
  void log(const std::string& line) override { send({{"event", "log"}, {"line", line}}); }
  void backend(const GlIdentity& gl) override {
    send({{"event", "backend"},
          {"platform", gl.platform},
          {"renderer", gl.renderer},
          {"version", gl.version},
          {"timing_source", gl.timing_source}});
  }
  void scene_planned(const std::string& scene, const std::vector<std::string>& log,
                     const std::string& bad_input) override {
    send({{"event", "scene"}, {"scene", scene}, {"log", log}, {"bad_input", bad_input}});
  }
  void phase(const std::string& scene, const std::string& resolution,
             const std::string& what) override {
    send({{"event", "phase"}, {"scene", scene}, {"resolution", resolution}, {"what", what}});
  }
  void job_started(const JobRecord& base) override {
    phases_.set("");
    send({{"event", "started"}, {"record", base.to_json()}});
  }
  void job_finished(JobRecord record) override {
    send({{"event", "finished"}, {"record", record.to_json()}});
  }
  void await_listener() override {
    const std::int64_t began = io_trace_enabled() ? monotonic_ns() : 0;
    send({{"event", "await"}});
    // The parent handles events in order: once it answers, it has stored
    // every record sent before, and writes nothing until the next event.
    std::string reply;
    char c = 0;
    while (c != '\n') {
      const ssize_t n = ::read(reply_fd_, &c, 1);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0 || reply.size() > 16)
        throw std::runtime_error("the parent process stopped answering");
      reply += c;
    }
    if (reply != kHeard)
      throw std::runtime_error("the parent process answered \"" + reply + "\", not \"heard\"");
    if (began != 0) write_trace({{"await", "the parent's answer", began, monotonic_ns()}});
  }
  void fatal(const std::string& message) { send({{"event", "fatal"}, {"message", message}}); }
  void job_phase(std::string_view phase) override { phases_.set(phase); }

 private:
  void send(const json& j) const {
    if (!write_fully(fd_, json_text(j) + "\n"))
      throw std::runtime_error("the parent process stopped listening");
  }
  int fd_, reply_fd_;
  PhaseBoard& phases_;
};

// The channel on which the parent answers the child's "await": a socket
// pair, so that answering a child that has just died is an error (EPIPE)
// rather than a SIGPIPE that kills the parent.
class ReplyChannel {
 public:
  ReplyChannel() {
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds_.data()) != 0)
      throw std::runtime_error(std::string("cannot create a socket pair: ") + std::strerror(errno));
  }
  ~ReplyChannel() {
    for (int& fd : fds_) close(fd);
  }
  ReplyChannel(const ReplyChannel&) = delete;
  ReplyChannel& operator=(const ReplyChannel&) = delete;
  int child_end() const { return fds_[1]; }
  // Each process keeps only its own end: the child's read then ends when
  // the parent's end closes.
  void keep_parent_end() { close(fds_[1]); }
  void keep_child_end() { close(fds_[0]); }
  // False when the child has gone; it then needs no answer.
  bool answer() const {
    const std::string text = kHeard;
    size_t done = 0;
    while (done < text.size()) {
      const ssize_t n = ::send(fds_[0], text.data() + done, text.size() - done, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      done += size_t(n);
    }
    return true;
  }

 private:
  static void close(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  std::array<int, 2> fds_{-1, -1};
};

// The parent's view of one child.
struct ChildState {
  std::optional<JobRecord> current;  // started, not finished
  Clock::time_point current_started;
  Clock::time_point last_finished;
  std::set<std::string> finished;
  std::deque<std::string> stderr_tail;
  std::string fatal;
  // Between the answer to "await" and the child's next event its frames
  // run: the stderr lines that come meanwhile are printed after them.
  bool rendering = false;
  std::vector<std::string> held_stderr;
};

std::string seconds_text(double s) { return format_number("%g", s); }

}  // namespace

IsolatedOutcome run_isolated(const Experiment& e, const RunOptions& o, const EmbreeChoice& embree,
                             size_t scene, const ResolutionWork& work, plan::ScenePlan* planned,
                             const TimeLimits& limits, ParentEvents& events) {
  const SceneVariant& sv = e.scenes.at(scene);
  const Resolution& res = e.resolutions.at(work.resolution);
  std::vector<const PlannedJob*> remaining = work.jobs;
  std::optional<GlIdentity> gl;
  IsolatedOutcome outcome;

  // A failed record for a job the child never finished.
  const auto fail = [&](JobRecord r, const std::string& reason, const ChildState& c,
                        bool timed_out) {
    r.status = JobStatus::Failed;
    r.reason = core::one_line_text(reason, core::kMessageChars);
    r.child_stderr.assign(c.stderr_tail.begin(), c.stderr_tail.end());
    events.job_finished(std::move(r));
    ++(timed_out ? outcome.timed_out : outcome.crashed);
  };

  while (!remaining.empty()) {
    ResolutionWork chunk = work;
    chunk.jobs = remaining;
    ReplyChannel replies;
    PhaseBoard phases;
    ChildProcess child = ChildProcess::start([&](int fd) {
      replies.keep_child_end();
      PipeEvents pipe(fd, replies.child_end(), phases);
      std::optional<JobExecutor> executor;
      try {
        executor.emplace(e, o, embree, pipe);
      } catch (const std::exception& ex) {
        pipe.fatal(ex.what());
        return kExitContextFailed;
      }
      executor->run_scene(scene, {chunk}, planned);  // the child's copy: the parent's stays
      return 0;
    });
    replies.keep_parent_end();
    const Clock::time_point child_started = Clock::now();
    ChildState c;
    const auto on_stderr = [&](const std::string& raw) {
      // A child's line may quote input (a scene's error): bounded, escaped.
      const std::string line = core::bounded_text(raw, core::kMessageChars);
      c.stderr_tail.push_back(line);
      if (c.stderr_tail.size() > kStderrTail) c.stderr_tail.pop_front();
      if (c.rendering)
        c.held_stderr.push_back(line);
      else
        events.child_stderr(line);
    };
    const auto done_rendering = [&] {
      c.rendering = false;
      for (const std::string& line : c.held_stderr) events.child_stderr(line);
      c.held_stderr.clear();
    };
    const auto on_message = [&](const std::string& line) {
      done_rendering();
      const json j = json::parse(line, nullptr, false);
      const std::string event = j.is_object() && j.contains("event") && j["event"].is_string()
                                    ? j["event"].get<std::string>()
                                    : "";
      try {
        if (event == "log") {
          events.log(j.at("line").get<std::string>());
        } else if (event == "backend") {
          gl = GlIdentity{j.at("platform").get<std::string>(), j.at("renderer").get<std::string>(),
                          j.at("version").get<std::string>(),
                          j.at("timing_source").get<std::string>()};
          events.backend(*gl);
        } else if (event == "scene") {
          events.scene_planned(j.at("scene").get<std::string>(),
                               j.at("log").get<std::vector<std::string>>(),
                               j.at("bad_input").get<std::string>());
        } else if (event == "phase") {
          events.phase(j.at("scene").get<std::string>(), j.at("resolution").get<std::string>(),
                       j.at("what").get<std::string>());
        } else if (event == "started") {
          c.current = JobRecord::from_json(j.at("record"));
          c.current_started = Clock::now();
          events.job_started(*c.current);
        } else if (event == "finished") {
          JobRecord r = JobRecord::from_json(j.at("record"));
          if (c.current && c.current->job_id == r.job_id) c.current.reset();
          c.finished.insert(r.job_id);
          c.last_finished = Clock::now();
          events.job_finished(std::move(r));
        } else if (event == "await") {
          // Every event before this one is done: the child may render.
          c.rendering = replies.answer();
        } else if (event == "fatal") {
          c.fatal = j.at("message").get<std::string>();
        } else {
          on_stderr("(a message the parent could not read: " + line.substr(0, 200) + ")");
        }
      } catch (const core::JobError& ex) {
        // Read, but not kept: the parent's own write failed (a full disk),
        // and its words say which file and why.
        on_stderr("(the parent could not keep the child's " + event +
                  " message: " + std::string(ex.what()) + ")");
      } catch (const std::exception& ex) {
        on_stderr("(a message the parent could not read: " + std::string(ex.what()) + ")");
      }
    };

    bool timed_out = false;
    const auto after = [](Clock::time_point t, double seconds) {
      return t +
             std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    };
    for (;;) {
      const Clock::time_point deadline = c.current ? after(c.current_started, limits.job_seconds)
                                         : !c.finished.empty()
                                             ? after(c.last_finished, limits.job_seconds)
                                             : after(child_started, limits.setup_seconds);
      const auto pumped = child.pump(deadline, on_message, on_stderr);
      if (pumped == ChildProcess::Pumped::Closed) break;
      if (pumped == ChildProcess::Pumped::TimedOut) {
        timed_out = true;
        child.kill();
        // Its last words: the pipes close once it is gone.
        const auto drain_until = Clock::now() + std::chrono::seconds(5);
        while (child.pump(drain_until, on_message, on_stderr) == ChildProcess::Pumped::Output) {
        }
        break;
      }
    }
    done_rendering();
    const int status = child.wait();
    std::erase_if(remaining, [&](const PlannedJob* j) { return c.finished.count(j->id) > 0; });
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExitContextFailed && !c.fatal.empty())
      throw std::runtime_error(c.fatal);

    std::string how = timed_out ? "" : "its process " + describe_wait_status(status);
    if (!timed_out && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      how +=
          ", not sent by shadowbench: the kernel's out-of-memory killer sends it, as does kill -9";
    if (!c.fatal.empty()) how += ": " + c.fatal;

    if (c.current) {
      JobRecord r = *c.current;
      r.duration_s = std::chrono::duration<double>(Clock::now() - c.current_started).count();
      // Where it was, and how to run it where a debugger can see it.
      const std::string phase = phases.read();
      const std::string in = phase.empty() ? "" : " in " + phase;
      std::string reason;
      if (timed_out)
        reason = "timed out after " + seconds_text(limits.job_seconds) +
                 " s (limits.job_seconds, run --job-timeout)";
      else
        reason = "crashed";
      reason += in;
      reason += timed_out ? "; its process was killed" : ": " + how;
      if (o.reproduce_command)
        if (const std::string command = o.reproduce_command(r.job_id); !command.empty())
          reason += "; reproduce in-process: " + command;
      const std::string id = r.job_id;
      fail(std::move(r), reason, c, timed_out);
      std::erase_if(remaining, [&](const PlannedJob* j) { return j->id == id; });
      continue;  // the jobs it did not reach, in a fresh child
    }
    if (remaining.empty()) break;
    // Died outside a job. After a finished job a fresh child goes on; before
    // any, it would only redo the same set-up.
    if (!c.finished.empty()) continue;
    const std::string reason =
        "the set-up of " + sv.name + " @ " + res.label() + " (scene, G-buffer, reference) " +
        (timed_out ? "timed out after " + seconds_text(limits.setup_seconds) +
                         " s (limits.setup_seconds); its process was killed"
                   : (WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "ended without a record: "
                                                                    : "failed: ") +
                         how);
    for (const PlannedJob* j : remaining) {
      JobRecord r = identity_record(
          e, o, embree, sv, work.inputs != nullptr ? *work.inputs : std::vector<core::InputFile>{},
          res, e.techniques[j->technique], gl ? gl->renderer : "", gl ? gl->version : "");
      if (gl) {
        r.gl_platform = gl->platform;
        r.timing_source = gl->timing_source;
      }
      fail(std::move(r), reason, c, timed_out);
    }
    break;
  }
  return outcome;
}

}  // namespace sb::run
