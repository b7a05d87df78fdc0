// Checkpoint and resume (solver/sim/checkpoint.hpp): a run stopped after any step
// and resumed — on another number of threads — writes the outputs an uninterrupted
// run writes, bit for bit; a checkpoint that does not fit is refused.
#include "solver/sim/checkpoint.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/interrupt.hpp"
#include "solver/sim/run.hpp"
#include "verification/support/command_line.hpp"
#include "verification/support/fields_reader.hpp"
#include "verification/support/hybrid_body.hpp"
#include "verification/support/scene_text.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"

namespace pdmpm::sim {
namespace {

namespace fs = std::filesystem;

nlohmann::json summary(const fs::path& dir) { return nlohmann::json::parse(test::read_text(dir / "summary.json")); }

// history.csv byte for byte; every frame's step, time and datasets bit for bit; the
// summary's metrics equal.
void expect_same_outputs(const fs::path& a, const fs::path& b, const std::vector<std::string>& fields) {
  EXPECT_EQ(test::read_text(a / "history.csv"), test::read_text(b / "history.csv"));
  EXPECT_EQ(summary(a)["metrics"], summary(b)["metrics"]);
  EXPECT_EQ(summary(a)["steps"], summary(b)["steps"]);
  EXPECT_EQ(test::read_text(a / "fields.xdmf"), test::read_text(b / "fields.xdmf"));
  const test::FieldsReader fa((a / "fields.h5").string()), fb((b / "fields.h5").string());
  ASSERT_EQ(fa.frames().size(), fb.frames().size());
  for (std::size_t k = 0; k < fa.frames().size(); ++k) {
    const auto &x = fa.frames()[k], &y = fb.frames()[k];
    ASSERT_EQ(x.name, y.name);
    EXPECT_EQ(x.time, y.time);
    for (const std::string& field : fields) {
      const auto u = fa.read(x, field), v = fb.read(y, field);
      ASSERT_EQ(u.size(), v.size()) << field;
      EXPECT_EQ(std::memcmp(u.data(), v.data(), u.size() * sizeof(double)), 0) << field << " at " << x.name;
    }
  }
}

// Runs the scene whole (1 thread) and stopped after `stop_after` (2 threads), resumes
// the stopped one (1 thread), and compares. Returns the summaries of the whole run and
// of the stopped one (what happened after the stop).
struct Summaries {
  nlohmann::json whole, stopped;
};
Summaries expect_resume_is_bitwise(const io::Scene& scene, std::int64_t stop_after,
                                   const std::vector<std::string>& fields) {
  Summaries out;
  test::ScratchDir dir("resume_" + scene.id);
  RunOptions whole;
  whole.out_dir = dir.fresh("whole");
  whole.progress = false;
  whole.threads = 1;
  out.whole = run_scene(scene, whole).summary;
  EXPECT_EQ(out.whole["status"], "completed");

  RunOptions part = whole;
  part.out_dir = dir.fresh("part");
  part.threads = 2;
  part.interrupt_at_step = stop_after;
  const RunResult stopped = run_scene(scene, part);
  out.stopped = stopped.summary;
  EXPECT_EQ(stopped.exit_code, kExitInterrupted);
  EXPECT_EQ(summary(part.out_dir)["status"], "interrupted");
  EXPECT_EQ(summary(part.out_dir)["steps"], stop_after);
  EXPECT_NE(stopped.message.find("pdmpm resume"), std::string::npos) << stopped.message;
  if (!fs::exists(part.out_dir / kCheckpointFile)) {
    ADD_FAILURE() << "no checkpoint";
    return out;
  }
  EXPECT_NO_THROW(test::FieldsReader((part.out_dir / "fields.h5").string()));  // readable as it stands
  EXPECT_FALSE(interrupt_requested());                                         // handled, not left for the next run

  RunOptions resumed = whole;
  resumed.out_dir = part.out_dir;
  resumed.resume = read_checkpoint(part.out_dir);
  EXPECT_EQ(resumed.resume->info.step, stop_after);
  const auto again = io::parse_scene_text(resumed.resume->info.scene_text, resumed.resume->info.scene_file);
  const RunResult finished = run_scene(again, resumed);
  EXPECT_EQ(finished.status, "completed") << finished.message;
  EXPECT_FALSE(fs::exists(part.out_dir / kCheckpointFile));  // done: nothing left to resume
  expect_same_outputs(whole.out_dir, part.out_dir, fields);
  return out;
}

void expect_bonds_break_after_the_stop(const Summaries& s) {
  EXPECT_GT(s.whole["metrics"]["broken_bonds"].get<std::int64_t>(),
            s.stopped["metrics"]["broken_bonds"].get<std::int64_t>());
}

// A notched PMB strip pulled apart: bonds break during the run, contact on.
test::SceneText cracking_strip(const std::string& model) {
  test::SceneText t;
  t.id = "strip_" + model;
  t.plane = "strain";
  t.max = {0.03, 0.015};
  t.model = model;
  t.poissons_ratio = model == "pmb" ? "" : "0.3";
  t.material_keys = "critical_stretch = 0.002\n" + test::flowing_keys(model);
  t.model_keys = model == "pmb" ? "[model.contact]\nenabled = true" : "";
  t.time = "steps = 240";
  t.tables = R"(
[[precrack]]
from = [0.0, 0.0075]
to = [0.008, 0.0075]
[[boundary]]
name = "bottom"
kind = "velocity"
region = { type = "box", min = [0, 0], max = [0.03, 0.001] }
value = [0, -8.0]
[[boundary]]
name = "top"
kind = "velocity"
region = { type = "box", min = [0, 0.014], max = [0.03, 0.015] }
value = [0, 8.0]
[[probe]]
name = "tip"
point = [0.01, 0.0075]
[output]
every = 40
history_every = 3
fields = ["displacement", "velocity", "damage", "stress"]
)";
  return t;
}

TEST(Checkpoint, PmbStripWithBreakingAndContactResumesBitwise) {
  const auto scene = cracking_strip("pmb").parse("strip_pmb.toml");
  const auto s = expect_resume_is_bitwise(scene, 101, {"position", "displacement", "velocity", "damage", "stress"});
  expect_bonds_break_after_the_stop(s);
}

TEST(Checkpoint, PlasticLpsStripResumesBitwise) {
  const auto scene = cracking_strip("lps_plastic").parse("strip_lps_plastic.toml");
  const auto s = expect_resume_is_bitwise(scene, 120, {"position", "displacement", "damage", "stress"});
  expect_bonds_break_after_the_stop(s);
}

// The stabilized hybrid PD: its sub-horizons are refitted where bonds broke; after a resume
// the first evaluation refits them from the restored bonds, bit for bit as the update would.
TEST(Checkpoint, HpdStripResumesBitwise) {
  const auto scene = cracking_strip("hpd").parse("strip_hpd.toml");
  const auto s = expect_resume_is_bitwise(scene, 77, {"position", "displacement", "damage"});
  expect_bonds_break_after_the_stop(s);
}

TEST(Checkpoint, MpmJ2PlateResumesBitwise) {
  test::SceneText t;
  t.id = "mpm_plate";
  t.model = "mpm";
  t.horizon_ratio = 0.0;
  t.max = {0.02, 0.01};
  t.material_keys = "constitutive = \"j2\"\nyield_stress = 300e6\ntangent_modulus = 2e9";
  t.time = "steps = 150";
  t.tables = R"(
[[boundary]]
name = "left"
kind = "fixed"
region = { type = "box", min = [-1, -1], max = [0.0005, 1] }
[[boundary]]
name = "right"
kind = "velocity"
region = { type = "box", min = [0.0195, -1], max = [1, 1] }
value = ["20", "free"]
moving = true   # the box's travel is state a resume must restore
[output]
every = 25
fields = ["displacement", "velocity", "stress", "eq_plastic_strain"]
)";
  expect_resume_is_bitwise(t.parse("mpm_plate.toml"), 64,
                           {"position", "displacement", "velocity", "stress", "eq_plastic_strain"});
}

TEST(Checkpoint, LpsBlockIn3dResumesBitwise) {
  test::SceneText t;
  t.id = "block3d";
  t.dimension = 3;
  t.min = {0.0, 0.0, 0.0};
  t.max = {0.008, 0.006, 0.006};
  t.time = "steps = 60";
  t.tables = R"(
[[boundary]]
name = "pull"
kind = "velocity"
region = { type = "box", min = [0.007, -1, -1], max = [1, 1, 1] }
value = ["3", "free", "free"]
[output]
every = 20
fields = ["displacement", "stress"]
)";
  expect_resume_is_bitwise(t.parse("block3d.toml"), 33, {"position", "displacement", "stress"});
}

// Regions expand and shrink after the stop: the regions, tips and conversions continue.
// The test plate pulled five times faster with a lower critical stretch, so its crack
// runs within 300 steps (41 expansions, 40 shrinks). Both couplings: the full-state one
// keeps state-only bonds, whose flags the checkpoint must carry.
class CheckpointHybrid : public ::testing::TestWithParam<const char*> {};

TEST_P(CheckpointHybrid, ExpandShrinkResumesBitwise) {
  auto t = test::hybrid_plate_scene(
      "mode = \"expand_shrink\"\npd_radius = 1.5\nexpand_trigger = 1\nexpand_radius = 2\nkeep_radius = 2\n"
      "audit_conversions = true\ncoupling = \"" +
          std::string(GetParam()) + "\"\n",
      "steps = 300");
  auto replace = [](std::string& text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  replace(t.material_keys, "critical_stretch = 0.01", "critical_stretch = 0.003");
  replace(t.tables, "\"2.0\"", "\"10.0\"");
  replace(t.tables, "\"-2.0\"", "\"-10.0\"");
  replace(t.tables, "frames = 3", "every = 60");
  t.tables += "history_every = 4\nfields = [\"displacement\", \"velocity\", \"damage\", \"von_mises\", \"method\"]\n";
  const auto scene = t.parse("hybrid_plate.toml");
  const auto s =
      expect_resume_is_bitwise(scene, 150, {"position", "displacement", "velocity", "damage", "von_mises", "method"});
  // The resumed part converts both ways, expands and shrinks.
  for (const char* event : {"expansions", "shrinks", "to_pd", "to_mpm"})
    EXPECT_GT(s.whole["events"][event].get<std::int64_t>(), s.stopped["events"][event].get<std::int64_t>()) << event;
}

INSTANTIATE_TEST_SUITE_P(Checkpoint, CheckpointHybrid, ::testing::Values("paper", "full_state"));

TEST(Checkpoint, PeriodicCheckpointsLeaveNoFileOnceTheRunEnds) {
  test::ScratchDir dir("periodic");
  const auto scene = cracking_strip("pmb").parse("strip.toml");
  RunOptions o;
  o.out_dir = dir.fresh("out");
  o.progress = false;
  o.checkpoint_every_steps = 50;
  EXPECT_EQ(run_scene(scene, o).status, "completed");
  EXPECT_FALSE(fs::exists(o.out_dir / kCheckpointFile));
}

TEST(Checkpoint, RunsWithoutCheckpointsSayWhyAndStillStopCleanly) {
  test::ScratchDir dir("no_checkpoint");
  test::SceneText t;
  t.id = "adr";
  t.time = "integrator = \"adr\"\nload_steps = 4";
  t.tables = R"(
[[boundary]]
name = "left"
kind = "fixed"
region = { type = "box", min = [-1, -1], max = [0.001, 1] }
[[boundary]]
name = "right"
kind = "displacement"
region = { type = "box", min = [0.029, -1], max = [1, 1] }
value = ["1e-5", "free"]
)";
  const auto scene = t.parse("adr.toml");
  RunOptions o;
  o.out_dir = dir.fresh("out");
  o.progress = false;
  o.checkpoint_every_steps = 2;
  EXPECT_THROW(run_scene(scene, o), InputError);
  EXPECT_FALSE(fs::exists(o.out_dir / "history.csv"));

  o.checkpoint_every_steps = 0;
  o.interrupt_at_step = 2;
  const RunResult r = run_scene(scene, o);
  EXPECT_EQ(r.exit_code, kExitInterrupted);
  EXPECT_NE(r.message.find("no checkpoint"), std::string::npos) << r.message;
  EXPECT_FALSE(fs::exists(o.out_dir / kCheckpointFile));
  EXPECT_EQ(summary(o.out_dir)["status"], "interrupted");
}

TEST(Checkpoint, ACheckpointFromAnotherBuildOrDamagedIsRefused) {
  test::ScratchDir dir("refused");
  const auto scene = cracking_strip("pmb").parse("strip.toml");
  RunOptions o;
  o.out_dir = dir.fresh("out");
  o.progress = false;
  o.interrupt_at_step = 10;
  ASSERT_EQ(run_scene(scene, o).exit_code, kExitInterrupted);
  const auto file = o.out_dir / kCheckpointFile;

  EXPECT_THROW(read_checkpoint(dir.path()), InputError);  // no checkpoint there
  {
    auto a = core::StateArchive::read(file);
    CheckpointInfo info;
    sync_info(a, info);
    info.build = "0000000";
    core::StateArchive b(core::StateArchive::Mode::save);
    sync_info(b, info);
    b.write(dir.path() / kCheckpointFile);
    try {
      read_checkpoint(dir.path());
      ADD_FAILURE() << "another build's checkpoint was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("written by pdmpm 0000000"), std::string::npos) << e.what();
    }
  }
  std::string bytes = test::read_text(file);
  bytes[bytes.size() / 3] ^= 0x01;
  std::ofstream(file, std::ios::binary) << bytes;
  EXPECT_THROW(read_checkpoint(o.out_dir), InputError);
}

// A checkpoint resumed against a scene of another size: the state does not fit.
TEST(Checkpoint, StateOfAnotherSceneDoesNotFit) {
  test::ScratchDir dir("other_scene");
  RunOptions o;
  o.out_dir = dir.fresh("out");
  o.progress = false;
  o.interrupt_at_step = 10;
  ASSERT_EQ(run_scene(cracking_strip("pmb").parse("strip.toml"), o).exit_code, kExitInterrupted);
  auto wider = cracking_strip("pmb");
  wider.max = {0.032, 0.015};
  o.interrupt_at_step = 0;
  o.resume = read_checkpoint(o.out_dir);
  EXPECT_THROW(run_scene(wider.parse("strip.toml"), o), core::StateMismatch);
  EXPECT_TRUE(fs::exists(o.out_dir / kCheckpointFile));  // still there to resume properly
}

// The command line with real signals: SIGKILL after a periodic checkpoint (nothing
// could be closed), SIGINT (checkpoint and exit 5); both resume to the whole run's outputs.
TEST(Checkpoint, CommandLineResumesAfterSigkillAndSigint) {
  test::ScratchDir dir("cli_resume");
  auto t = cracking_strip("pmb");
  t.time = "steps = 3000";
  t.tables += "\n";
  const auto scene_file = dir.path() / "strip.toml";
  std::ofstream(scene_file) << t.toml();
  const std::string scene = scene_file.string();
  const auto whole = dir.fresh("whole");
  ASSERT_EQ(test::run_pdmpm(fmt::format("run {} -o {} -q -t 1", scene, whole.string())).status, 0);

  for (const char* signal : {"KILL", "INT"}) {
    const auto out = dir.fresh(std::string("stopped_") + signal);
    // Start the run, wait for its first periodic checkpoint, send the signal.
    const auto r =
        test::run_command(fmt::format("{}/pdmpm run {} -o {} -q -t 2 --checkpoint-every 20 & p=$!; "
                                      "while [ ! -f {}/{} ]; do sleep 0.01; done; kill -{} $p; wait $p; echo exit=$?",
                                      PDMPM_BINARY_DIR, scene, out.string(), out.string(), kCheckpointFile, signal));
    const std::string expected = std::string(signal) == "KILL" ? "exit=137" : fmt::format("exit={}", kExitInterrupted);
    ASSERT_NE(r.output.find(expected), std::string::npos) << r.output;
    const auto resumed = test::run_pdmpm(fmt::format("resume {} -q -t 1", out.string()));
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    expect_same_outputs(whole, out, {"position", "displacement", "velocity", "damage", "stress"});
    for (const auto& entry : fs::directory_iterator(out))  // the killed run's staging directory is gone
      EXPECT_NE(entry.path().filename().string().rfind(".partial-", 0), 0u) << entry.path();
  }
}

TEST(Checkpoint, CommandLineRefusesBadIntervalsAndMissingCheckpoints) {
  test::ScratchDir dir("cli_refuse");
  const auto scene_file = dir.path() / "strip.toml";
  std::ofstream(scene_file) << cracking_strip("pmb").toml();
  for (const char* bad : {"0", "-5", "1.5", "5x", "m", "nan"}) {
    const auto r = test::run_pdmpm(
        fmt::format("run {} -o {} -q --checkpoint-every {}", scene_file.string(), dir.fresh("x").string(), bad));
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--checkpoint-every"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "x"));
  const auto r = test::run_pdmpm("resume " + dir.fresh("nothing").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("no checkpoint here"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace pdmpm::sim
