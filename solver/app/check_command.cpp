// `pdmpm check SCENE`: what a run of the scene would be and cost, without running it.
// The scene is validated and built exactly as `pdmpm run` builds it (same errors, same
// exit status 2), then advanced a few steps in a scratch directory that is deleted
// afterwards — the calibration — and the run's wall time extrapolated from those
// steps. Users trade resolution for time before they spend it.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include "solver/app/commands.hpp"
#include "solver/core/error.hpp"
#include "solver/io/progress.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/output_schedule.hpp"
#include "solver/sim/run.hpp"
#include "solver/sim/run_metrics.hpp"

namespace pdmpm::app {
namespace {

namespace fs = std::filesystem;

// A scratch directory removed when it goes out of scope, whatever happens.
struct ScratchDirectory {
  fs::path path = fs::temp_directory_path() / fmt::format("pdmpm-check-{}", ::getpid());
  ~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// The scene advanced `steps` steps (0: built only) in scratch, without fields: its
// summary, and the seconds the call took (building included).
struct Trial {
  nlohmann::json summary;
  double seconds = 0.0;
};
Trial trial_run(const io::Scene& scene, std::int64_t steps, int threads, const fs::path& out) {
  io::Scene trial = scene;
  trial.time.steps = steps;
  trial.time.end_time.reset();
  sim::RunOptions opt;
  opt.out_dir = out;
  opt.threads = threads;
  opt.progress = false;
  opt.write_fields = false;
  const auto t0 = std::chrono::steady_clock::now();
  const sim::RunResult r = sim::run_scene(trial, opt);
  if (r.exit_code != 0) throw RunError(r.message);
  return {r.summary, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

void describe(const io::Scene& scene, const nlohmann::json& s) {
  fmt::print("{} ({}): valid\n", scene.id, scene.file);
  const std::string solver = s.value("solver", std::string("pd")), model = s.value("model", scene.model);
  fmt::print("  method      {}{}, {}D{}\n", solver, model == solver ? "" : ", model " + model, scene.dimension,
             scene.dimension == 2 && s.contains("setting") ? ", " + s["setting"].get<std::string>() : "");
  std::string body = fmt::format("{} particles", s.value("particles", 0L));
  if (s.contains("bonds")) body += fmt::format(", {} bond sides", s["bonds"].get<long>());
  if (s.contains("grid_nodes")) body += fmt::format(", {} grid nodes", s["grid_nodes"].get<long>());
  fmt::print("  body        {}\n", body);
}

}  // namespace

int check_command(const CheckArgs& args) {
  try {
    const io::Scene scene = io::parse_scene(args.scene);
    ScratchDirectory scratch;
    const bool quasi_static = scene.time.integrator == io::Integrator::adr;
    const bool calibrate = !quasi_static && args.calibration_seconds > 0.0;
    // First trial: built, and a few steps when calibrating (their wall time sizes the second).
    const std::int64_t n1 = calibrate ? std::min<std::int64_t>(10, scene.time.steps.value_or(10)) : 0;
    const double others = calibrate ? sim::other_running_processes() : -1.0;  // before the calibration runs
    const Trial first = trial_run(scene, n1, args.threads, scratch.path / "first");
    const nlohmann::json& s = first.summary;
    describe(scene, s);
    fmt::print("  memory      {} peak (the process, built{})\n",
               io::format_engineering(s.value("peak_memory_bytes", 0.0), "B"),
               n1 > 0 ? fmt::format(" and {} steps run", n1) : "");
    if (quasi_static) {
      fmt::print(
          "  time        quasi-static (adaptive dynamic relaxation): {} load steps of at most {} iterations;\n"
          "              no wall-time estimate, the iterations depend on convergence\n",
          scene.time.load_steps, scene.time.max_steps);
      return 0;
    }
    const sim::StepPlan plan = sim::plan_steps(scene.time, s.value("dt", 0.0));
    fmt::print("  time        dt = {:.4g} s, {} steps to t = {:.4g} s\n", plan.dt, plan.steps, plan.end_time);
    if (!calibrate || plan.steps <= n1) return 0;
    // Second trial: about calibration_seconds of steps more; the difference of the two
    // runs' own wall times (the stepping loop and its start, the same in both) is the
    // cost of a step. The difference of the calls' times also holds building the body
    // twice, whose spread on a large body exceeded the steps' time: a 160 000-particle
    // plate got 0 s per step and an estimate of 2 s for an 80-minute run.
    const double rough = std::max(first.summary.value("wall_time_s", 0.0) / static_cast<double>(n1), 1e-9);
    const std::int64_t more =
        std::clamp<std::int64_t>(static_cast<std::int64_t>(args.calibration_seconds / rough), n1, plan.steps - n1);
    const Trial second = trial_run(scene, n1 + more, args.threads, scratch.path / "second");
    const double per_step = std::max(
        0.0, (second.summary.value("wall_time_s", 0.0) - s.value("wall_time_s", 0.0)) / static_cast<double>(more));
    const double fixed = std::max(0.0, first.seconds - per_step * static_cast<double>(n1));
    const int threads = s.value("threads", 0);
    fmt::print("  cost        {} per step on {} thread{} (timed over {} steps), {} to build and start\n",
               io::format_engineering(per_step, "s"), threads, threads == 1 ? "" : "s", more,
               io::format_engineering(fixed, "s"));
    fmt::print("  estimate    about {} for the run, without field output{}\n",
               io::format_duration(fixed + per_step * static_cast<double>(plan.steps)),
               scene.method == io::Method::hybrid ? " (PD regions born later make it longer)" : "");
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    if (sim::cores_taken(others, cores, threads))
      fmt::print(
          "  note        the machine was busy ({:.0f} other process{} running on {} cores): a run timed while\n"
          "              other work holds the cores it needs can take many times as long as on a quiet machine\n",
          others, others == 1.0 ? "" : "es", cores);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "pdmpm: error: " << e.what() << "\n";
    return 2;
  } catch (const RunError& e) {
    std::cerr << "pdmpm: the scene is valid, but its calibration steps failed: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "pdmpm: internal error: " << e.what() << "\n";
    return 4;
  }
}

}  // namespace pdmpm::app
