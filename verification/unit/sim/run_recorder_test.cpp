// RunRecorder with a fake run: what every run writes is written once, here —
// history on schedule, frames, the summary keys, all or nothing.
#include "solver/sim/run_recorder.hpp"
#include "verification/support/output_files.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pdmpm::sim {
namespace {

namespace fs = std::filesystem;

io::Scene tiny_scene() {
  io::Scene s;
  s.file = "fake.toml";
  s.id = "fake";
  s.description = "a run that moves nothing";
  s.output.every = 5;
  s.output.history_every = 2;
  return s;
}

struct Fixture {
  fs::path dir = fs::temp_directory_path() / ("pdmpm_recorder_" + std::to_string(::getpid()));
  io::Scene scene = tiny_scene();
  RunOptions options;
  Fixture() {
    fs::remove_all(dir);
    options.out_dir = dir;
    options.progress = false;
  }
  ~Fixture() { fs::remove_all(dir); }
};

// A fake method's loop: ten steps, a row when due, a frame when due.
RunResult fake_run(Fixture& f, bool unstable_at_7) {
  RunRecorder rec(f.scene, f.options);
  rec.plan(10, 0.1);
  rec.start({"step", "time", "value"}, 2, 1.0);
  std::int64_t done = 0;
  for (std::int64_t step = 0; step <= 10; ++step) {
    const double t = 0.1 * static_cast<double>(step);
    done = step;
    if (unstable_at_7 && step == 7) {
      rec.stop("unstable", "the fake run blew up at step 7");
      rec.write_history({static_cast<double>(step), t, 1e300});
      break;
    }
    if (rec.history_due(step)) rec.write_history({static_cast<double>(step), t, 2.0 * t});
    if (rec.frame_due(step) && rec.writes_fields()) {
      const std::vector<double> pos{0, 0, 0, 1, 0, 0};
      rec.write_frame(step, t, pos, {{"value", io::FieldKind::scalar, {t, t}}});
    }
  }
  return rec.finish(done, 0.1 * static_cast<double>(done), 0, 2, {{"solver", "fake"}, {"dimension", 2}});
}

TEST(RunRecorder, WritesHistoryFramesAndTheCommonSummary) {
  Fixture f;
  const auto r = fake_run(f, false);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.status, "completed");
  for (const char* name : {"history.csv", "fields.h5", "fields.xdmf", "summary.json"})
    EXPECT_TRUE(fs::exists(f.dir / name)) << name;
  // history every 2 steps and at the last: 0, 2, 4, 6, 8, 10 → header + 6 rows.
  const std::string history = test::read_text(f.dir / "history.csv");
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), 7) << history;
  const auto& s = r.summary;
  for (const char* key :
       {"scene", "file", "description", "status", "message", "steps", "steps_requested", "threads", "wall_time_s",
        "peak_memory_bytes", "particle_steps_per_second", "provenance", "solver", "warnings"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["steps"], 10);
  EXPECT_EQ(s["steps_requested"], 10);
  EXPECT_EQ(s["solver"], "fake");
  // frames every 5 steps: 0, 5, 10.
  const std::string xdmf = test::read_text(f.dir / "fields.xdmf");
  std::size_t grids = 0;
  for (std::size_t at = xdmf.find("<Time "); at != std::string::npos; at = xdmf.find("<Time ", at + 1)) ++grids;
  EXPECT_EQ(grids, 3u) << xdmf;
}

TEST(RunRecorder, AnEarlyStopIsReportedWithExitCodeThree) {
  Fixture f;
  const auto r = fake_run(f, true);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.summary["status"], "unstable");
  EXPECT_EQ(r.summary["message"], "the fake run blew up at step 7");
  EXPECT_EQ(r.summary["steps"], 7);
  EXPECT_TRUE(fs::exists(f.dir / "summary.json"));
}

TEST(RunRecorder, AWarningIsListedOncePerKeyAndTheRunGoesOn) {
  Fixture f;
  RunRecorder rec(f.scene, f.options);
  rec.plan(2, 0.1);
  rec.start({"step"}, 2, 0.2);
  rec.warn("null_space", "first text", 1, 0.1);
  rec.warn("null_space", "the same condition again", 2, 0.2);
  rec.warn("other", "another condition", 2, 0.2);
  const auto r = rec.finish(2, 0.2, 0, 2, {{"solver", "fake"}, {"dimension", 2}});
  EXPECT_EQ(r.exit_code, 0);
  const auto& w = r.summary["warnings"];
  ASSERT_EQ(w.size(), 2u) << w.dump();
  EXPECT_EQ(w[0]["key"], "null_space");
  EXPECT_EQ(w[0]["text"], "first text");
  EXPECT_EQ(w[0]["step"], 1);
  EXPECT_EQ(w[0]["time"], 0.1);
  EXPECT_EQ(w[1]["key"], "other");
}

TEST(RunRecorder, NothingIsLeftWhenTheRunThrows) {
  Fixture f;
  try {
    RunRecorder rec(f.scene, f.options);
    rec.plan(10, 0.1);
    rec.start({"step"}, 2, 1.0);
    rec.write_history({0.0});
    throw std::runtime_error("the method failed");
  } catch (const std::runtime_error&) {}
  ASSERT_TRUE(fs::exists(f.dir));  // created by the run, left empty
  EXPECT_TRUE(fs::is_empty(f.dir)) << "a staged file or directory was left behind";
}

}  // namespace
}  // namespace pdmpm::sim
