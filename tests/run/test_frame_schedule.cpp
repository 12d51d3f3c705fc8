// The frame schedule of one job (run/frame_schedule.h) over a fake target
// that logs each call: the orders docs/design.md and docs/ci.md describe
// (compile frame untimed and alone, ABBA control frames next to warm-up and
// timed frames, the job's own frame last, fine frames after, turns before
// each block of timed frames), and which frames' times the record keeps.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "run/frame_schedule.h"

namespace sb {

using record::TimingRecord;
using run::FrameSchedule;
using run::FrameTarget;
using run::time_frames;

namespace {

// Logs "job", "fine", "control" or "turn" per call. Each frame takes a time
// of its own: job frames 1, 2, 3, ... ms in call order, control frames
// 100, 200, 300, ... ms, so a sample tells which frame it came from.
class LoggingTarget : public FrameTarget {
 public:
  std::vector<std::string> calls;

  gl::PassTimer::Frame job_frame(const std::string&, gl::PassDetail detail) override {
    calls.push_back(detail == gl::PassDetail::Fine ? "fine" : "job");
    const double ms = ++job_frames_;
    if (detail == gl::PassDetail::Fine)
      return {{{"shared:gbuffer", 0.25}, {"depth", ms / 4}, {"blur", ms / 2}}, ms};
    return {{{"shared:gbuffer", 0.25}, {"technique", ms / 2}, {"shared:shading", 0.25}}, ms};
  }
  gl::PassTimer::Frame control_frame(const std::string&) override {
    calls.push_back("control");
    return {{{"technique", 1.0}}, 100.0 * ++control_frames_};
  }
  void take_turn() override { calls.push_back("turn"); }

 private:
  int job_frames_ = 0, control_frames_ = 0;
};

using Calls = std::vector<std::string>;

FrameSchedule schedule(int warmup, int timed) {
  FrameSchedule s;
  s.job = "pcf/k=5";
  s.warmup_frames = warmup;
  s.timed_frames = timed;
  return s;
}

TEST(FrameSchedule, WithoutControlCompileWarmupThenTimedFrames) {
  LoggingTarget target;
  const TimingRecord t = time_frames(target, schedule(2, 3));
  // compile, 2 warm-up, 3 timed.
  EXPECT_EQ(target.calls, Calls(6, "job"));
  EXPECT_EQ(t.compile_frames, 1);
  EXPECT_EQ(t.warmup_frames, 2);
  EXPECT_EQ(t.timed_frames, 3);
  // Only the timed frames (the 4th to 6th call) are samples.
  EXPECT_EQ(t.frame.samples, (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(t.technique.samples, (std::vector<double>{2, 2.5, 3}));
  EXPECT_EQ(t.shared.at("gbuffer").samples, (std::vector<double>{0.25, 0.25, 0.25}));
  EXPECT_FALSE(t.control.has_value());
  EXPECT_FALSE(t.fine.has_value());
}

TEST(FrameSchedule, ZeroWarmupStillHasAnUntimedCompileFrame) {
  LoggingTarget target;
  const TimingRecord t = time_frames(target, schedule(0, 2));
  EXPECT_EQ(target.calls, Calls(3, "job"));
  EXPECT_EQ(t.frame.samples, (std::vector<double>{2, 3}));
}

TEST(FrameSchedule, ControlFramesInAbbaOrderAndTheJobsFrameLast) {
  LoggingTarget target;
  FrameSchedule s = schedule(1, 2);
  s.control = "none";
  const TimingRecord t = time_frames(target, s);
  // The compile frame alone; warm-up 0 job-control, timed 1 control-job,
  // timed 2 job-control; a control frame came last, so one more job frame.
  EXPECT_EQ(target.calls,
            (Calls{"job", "job", "control", "control", "job", "job", "control", "job"}));
  // Job frames by call: compile 1, warm-up 2, timed 3 and 4 (the read-back
  // frame, 5, is not timed); control frames: warm-up 100, timed 200, 300.
  EXPECT_EQ(t.frame.samples, (std::vector<double>{3, 4}));
  ASSERT_TRUE(t.control.has_value());
  EXPECT_EQ(t.control->technique, "none");
  EXPECT_EQ(t.control->frame.samples, (std::vector<double>{200, 300}));
  EXPECT_EQ(t.control->frame_ratio.samples, (std::vector<double>{3.0 / 200, 4.0 / 300}));
}

TEST(FrameSchedule, NoExtraJobFrameWhenTheJobsFrameCameLast) {
  LoggingTarget target;
  FrameSchedule s = schedule(0, 2);
  s.control = "none";
  time_frames(target, s);
  EXPECT_EQ(target.calls, (Calls{"job", "job", "control", "control", "job"}));
}

TEST(FrameSchedule, FineFramesFollowTheTimedOnes) {
  LoggingTarget target;
  FrameSchedule s = schedule(1, 2);
  s.pass_detail = gl::PassDetail::Fine;
  const TimingRecord t = time_frames(target, s);
  EXPECT_EQ(target.calls, (Calls{"job", "job", "job", "job", "fine", "fine"}));
  EXPECT_EQ(t.pass_timing, "fine");
  EXPECT_EQ(t.frame.samples, (std::vector<double>{3, 4}));
  ASSERT_TRUE(t.fine.has_value());
  EXPECT_EQ(t.fine->frames, 2);
  EXPECT_EQ(t.fine->pass_order, (std::vector<std::string>{"depth", "blur"}));
  EXPECT_EQ(t.fine->frame.samples, (std::vector<double>{5, 6}));
  EXPECT_EQ(t.fine->passes.at("depth").samples, (std::vector<double>{1.25, 1.5}));
  // The sum of the passes per fine frame.
  EXPECT_EQ(t.fine->technique.samples, (std::vector<double>{3.75, 4.5}));
}

TEST(FrameSchedule, FineFramesAreTheJobsOwnAfterAControlFrame) {
  LoggingTarget target;
  FrameSchedule s = schedule(0, 1);
  s.control = "none";
  s.pass_detail = gl::PassDetail::Fine;
  time_frames(target, s);
  // The fine frame is the job's: no read-back frame before it.
  EXPECT_EQ(target.calls, (Calls{"job", "job", "control", "fine"}));
}

TEST(FrameSchedule, TurnsBeforeEachBlockOfTimedFrames) {
  LoggingTarget target;
  FrameSchedule s = schedule(1, 5);
  s.turn_block_frames = 2;
  time_frames(target, s);
  // compile, warm-up, then blocks of two timed frames (the last one short).
  EXPECT_EQ(target.calls,
            (Calls{"job", "job", "turn", "job", "job", "turn", "job", "job", "turn", "job"}));
}

TEST(FrameSchedule, TheLoadIsReadBeforeTheFirstTimedFrameAndAfterTheLast) {
  LoggingTarget target;
  FrameSchedule s = schedule(2, 3);
  double load = 0.5;
  s.load_average = [&]() -> std::optional<double> {
    target.calls.push_back("load");
    return load += 1.0;
  };
  s.usable_cores = 3;
  s.noise_threshold = 0.25;
  const TimingRecord t = time_frames(target, s);
  EXPECT_EQ(target.calls, (Calls{"job", "job", "job", "load", "job", "job", "job", "load"}));
  ASSERT_TRUE(t.noise.has_value());
  EXPECT_EQ(t.noise->load_average_start, 1.5);
  EXPECT_EQ(t.noise->load_average_end, 2.5);
  EXPECT_EQ(t.noise->usable_cores, 3);
  EXPECT_EQ(t.noise->threshold, 0.25);
}

TEST(FrameSchedule, TheRecordJudgesItsMediansIntervalsByTheThreshold) {
  // Timed job frames 2, 3, ..., 11 ms (warm-up 0): median 6.5, the interval
  // [x_(2), x_(9)] = [3, 10], half-width 3.5 / 6.5 = 0.538.
  LoggingTarget target;
  FrameSchedule s = schedule(0, 10);
  s.noise_threshold = 0.5;
  TimingRecord t = time_frames(target, s);
  ASSERT_TRUE(t.noise.has_value());
  EXPECT_DOUBLE_EQ(t.noise->frame_ci_rel, 3.5 / 6.5);
  EXPECT_TRUE(t.noise->noisy);
  EXPECT_FALSE(t.noise->load_average_start.has_value());  // no probe: not read
  LoggingTarget again;
  s.noise_threshold = 0.6;
  t = time_frames(again, s);
  EXPECT_FALSE(t.noise->noisy);
}

// Frame times from functions of the frame's number (1, 2, ...), each kind
// counted apart; no passes.
class ScriptedTarget : public FrameTarget {
 public:
  std::function<double(int)> job_ms, control_ms;
  gl::PassTimer::Frame job_frame(const std::string&, gl::PassDetail) override {
    return {{}, job_ms(++jobs_)};
  }
  gl::PassTimer::Frame control_frame(const std::string&) override {
    return {{}, control_ms(++controls_)};
  }
  void take_turn() override {}

 private:
  int jobs_ = 0, controls_ = 0;
};

// The k-th number of the base-2 van der Corput sequence: fills [0, 1)
// evenly at every prefix, so a sample's quantiles close in on the uniform
// distribution's as frames are added, without randomness.
double van_der_corput(int k) {
  double v = 0, place = 0.5;
  for (; k > 0; k >>= 1, place /= 2)
    if (k & 1) v += place;
  return v;
}

FrameSchedule auto_schedule(double target, int max_frames, double max_seconds) {
  FrameSchedule s = schedule(0, 10);
  s.auto_frames = FrameSchedule::AutoFrames{target, max_frames, max_seconds};
  return s;
}

TEST(FrameSchedule, AutoFramesStopAtTheFirstBlockWhoseIntervalIsWithinTheTarget) {
  // Frames of 10 + U(0, 1) ms: the median's interval narrows as 1/sqrt(n)
  // (about 0.093 / sqrt(n) of the median), so 1 % needs about 90 frames.
  ScriptedTarget target;
  target.job_ms = [](int k) { return 10 + van_der_corput(k); };
  const TimingRecord t = time_frames(target, auto_schedule(0.01, 1000, 1e9));
  ASSERT_TRUE(t.auto_frames.has_value());
  EXPECT_EQ(t.auto_frames->stop, "target");
  EXPECT_EQ(t.auto_frames->block, 10);
  EXPECT_EQ(t.timed_frames % 10, 0);
  EXPECT_GE(t.timed_frames, 60);
  EXPECT_LE(t.timed_frames, 150);
  EXPECT_EQ(t.frame.samples.size(), static_cast<size_t>(t.timed_frames));
  // The record's own interval is within the target, and a block fewer was not.
  EXPECT_LE(t.frame.median_ci_rel, 0.01);
  EXPECT_DOUBLE_EQ(t.auto_frames->half_width, t.frame.median_ci_rel);
  const std::vector<double> fewer(t.frame.samples.begin(), t.frame.samples.end() - 10);
  EXPECT_GT(record::Series::of(fewer).median_ci_rel, 0.01);
}

TEST(FrameSchedule, AutoFramesStopAtTheFrameBoundWhenTheIntervalNeverNarrows) {
  ScriptedTarget target;
  target.job_ms = [](int k) { return k % 2 ? 1.0 : 100.0; };
  const TimingRecord t = time_frames(target, auto_schedule(0.03, 45, 1e9));
  ASSERT_TRUE(t.auto_frames.has_value());
  EXPECT_EQ(t.auto_frames->stop, "max_frames");
  EXPECT_EQ(t.timed_frames, 40);  // a fifth block would pass 45
  EXPECT_GT(t.auto_frames->half_width, 0.03);
  EXPECT_TRUE(t.noise->noisy);
}

TEST(FrameSchedule, AutoFramesStopAtTheTimeBound) {
  ScriptedTarget target;
  target.job_ms = [](int k) { return k % 2 ? 1.0 : 100.0; };
  FrameSchedule s = auto_schedule(0.03, 1000, 2.5);
  double now = 0;
  s.clock = [&now] { return now++; };  // a second per look
  const TimingRecord t = time_frames(target, s);
  ASSERT_TRUE(t.auto_frames.has_value());
  EXPECT_EQ(t.auto_frames->stop, "max_seconds");
  EXPECT_EQ(t.timed_frames, 30);  // looks at 1 s, 2 s, then 3 s >= 2.5 s
  EXPECT_DOUBLE_EQ(t.auto_frames->seconds, 3.0);
}

TEST(FrameSchedule, AutoFramesJudgeTheRatioToTheControlToo) {
  // Steady job frames, control frames 1 or 100 ms: the ratio never settles.
  ScriptedTarget target;
  target.job_ms = [](int) { return 10.0; };
  target.control_ms = [](int k) { return k % 2 ? 1.0 : 100.0; };
  FrameSchedule s = auto_schedule(0.03, 30, 1e9);
  s.control = "none";
  const TimingRecord t = time_frames(target, s);
  ASSERT_TRUE(t.auto_frames.has_value());
  EXPECT_EQ(t.auto_frames->stop, "max_frames");
  EXPECT_EQ(t.timed_frames, 30);
  EXPECT_EQ(t.control->frame.samples.size(), 30u);
  EXPECT_EQ(t.frame.median_ci_rel, 0.0);
}

TEST(FrameSchedule, FixedFramesHaveNoAutoRecord) {
  ScriptedTarget target;
  target.job_ms = [](int k) { return k % 2 ? 1.0 : 100.0; };
  const TimingRecord t = time_frames(target, schedule(0, 10));
  EXPECT_EQ(t.timed_frames, 10);
  EXPECT_FALSE(t.auto_frames.has_value());
}

}  // namespace
}  // namespace sb
