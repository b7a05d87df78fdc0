#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "solver/app/commands.hpp"
#include "solver/core/error.hpp"
#include "solver/core/state_archive.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/checkpoint.hpp"
#include "solver/sim/interrupt.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::app {
namespace {

// "--checkpoint-every": a whole number of steps ("5000"), or wall time with a unit
// ("90s", "30m", "2h").
void parse_checkpoint_interval(const std::string& text, sim::RunOptions& opt) {
  if (text.empty()) return;
  const auto fail = [&] {
    throw InputError(
        "", "--checkpoint-every",
        fmt::format("'{}' is neither a number of steps (e.g. 5000) nor a wall time (e.g. 90s, 30m, 2h)", text));
  };
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    fail();
  }
  const std::string unit = text.substr(used);
  if (!(value > 0.0) || !std::isfinite(value)) fail();
  if (unit.empty()) {
    if (value != std::floor(value) || value > 9e18) fail();
    opt.checkpoint_every_steps = static_cast<std::int64_t>(value);
  } else if (unit == "s" || unit == "m" || unit == "h") {
    opt.checkpoint_every_seconds = value * (unit == "s" ? 1.0 : unit == "m" ? 60.0 : 3600.0);
  } else {
    fail();
  }
}

// Runs the scene; the process that speaks (the only one, or process 0 of a distributed
// run) reports the end on stderr.
int run_and_report(const io::Scene& scene, const sim::RunOptions& opt, bool quiet, bool speaks) {
  sim::install_interrupt_handlers();  // every process: a signal stops them all after the same step
  const sim::RunResult r = sim::run_scene(scene, opt);
  if (!speaks) return r.exit_code;
  const auto& s = r.summary;
  if (r.exit_code != 0) {
    std::cerr << "pdmpm: " << r.message << "\n";
    std::cerr << "pdmpm: outputs up to " << (r.status == "interrupted" ? "the interruption" : "the failure")
              << " are in " << opt.out_dir.string() << "\n";
    return r.exit_code;
  }
  if (!quiet) {
    const std::string rate = !s.contains("bond_updates_per_second")  // mpm, hybrid
        ? fmt::format("{:.3g} particle-steps/s", s["particle_steps_per_second"].get<double>())
        : fmt::format("{} bonds, {:.3g} bond updates/s", s["bonds"].get<long>(),
                      s["bond_updates_per_second"].get<double>());
    std::cerr << fmt::format("pdmpm: {} done: {} particles, {} steps of {:.4g} s in {:.3g} s ({}) → {}\n", scene.id,
                             s["particles"].get<long>(), s["steps"].get<long>(), s["dt"].get<double>(),
                             s["wall_time_s"].get<double>(), rate, opt.out_dir.string());
  }
  return 0;
}

// An error's message (its exit status: exit_status_of, core/error.hpp).
std::string describe(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    return fmt::format("error: {}", e.what());
  } catch (const core::StateMismatch& e) {
    return fmt::format("error: the checkpoint does not fit this run: {}", e.what());
  } catch (const RunError& e) {
    return fmt::format("run failed: {}", e.what());
  } catch (const std::exception& e) {
    return fmt::format("internal error: {}", e.what());
  }
}

// Exit status of an exception a run or resume threw, its message on stderr. In a
// distributed run, input errors are met alike by every process (each reads the same
// scene and checks the whole body): process 0 speaks for all. An error the others
// have learnt of (SharedFailure) is reported by the process that met it. Any other
// error may be one process's alone: it says which and stops the others (MPI_Abort),
// which would wait for it.
int report_error(const dist::Communicator* comm) {
  std::exception_ptr error = std::current_exception();
  bool shared = false;
  try {
    throw;
  } catch (const OtherProcessFailed& e) {
    return e.exit_status();  // the process that failed has reported it
  } catch (const SharedFailure& e) {
    shared = true;
    try {
      std::rethrow_if_nested(e);
    } catch (...) {
      error = std::current_exception();
    }
  } catch (...) {}
  const int status = exit_status_of(error);
  const std::string text = describe(error);
  const bool distributed = comm && comm->size() > 1;
  if (!distributed || shared || (status == 2 && comm->rank() == 0)) std::cerr << "pdmpm: " << text << "\n";
  if (!distributed || shared || status == 2) return status;
  std::cerr << fmt::format("pdmpm (process {} of {}): {}\n", comm->rank(), comm->size(), text);
  comm->abort(status);
}

}  // namespace

int run_command(const RunArgs& args, const dist::Communicator* comm) {
  // Process 0 of a distributed run writes the outputs and reports; the others are quiet.
  const bool speaks = !comm || comm->rank() == 0;
  try {
    sim::RunOptions opt;
    parse_checkpoint_interval(args.checkpoint_every, opt);
    const io::Scene scene = io::parse_scene(args.scene);
    opt.out_dir = args.out.empty() ? std::filesystem::path("out") / scene.id : std::filesystem::path(args.out);
    opt.threads = args.threads;
    opt.progress = !args.quiet && speaks;
    opt.write_fields = !args.no_fields;
    opt.interrupt_at_step = args.stop_after;
    opt.comm = comm;
    return run_and_report(scene, opt, args.quiet, speaks);
  } catch (...) {
    return report_error(comm);
  }
}

int resume_command(const ResumeArgs& args, const dist::Communicator* comm) {
  const bool speaks = !comm || comm->rank() == 0;
  try {
    sim::RunOptions opt;
    parse_checkpoint_interval(args.checkpoint_every, opt);
    if (comm && comm->size() > 1) {
      // Each process reads its own file, process 0 first (a checkpoint of another build or
      // process count is reported once); a missing or damaged file stops them all.
      for (const bool first : {true, false}) {
        std::exception_ptr failure;
        if (first == (comm->rank() == 0)) {
          try {
            opt.resume = sim::read_checkpoint(args.dir, comm->rank(), comm->size());
          } catch (...) {
            failure = std::current_exception();
          }
        }
        dist::agree_on_failure(*comm, failure);
      }
      const auto step = static_cast<double>(opt.resume->info.step);
      if (comm->min(step) != comm->max(step))
        throw InputError(args.dir, "",
                         "the processes' checkpoint files are of different steps (a run killed while writing them): "
                         "run the scene again");
    } else {
      opt.resume = sim::read_checkpoint(args.dir);
    }
    const io::Scene scene = io::parse_scene_text(opt.resume->info.scene_text, opt.resume->info.scene_file);
    opt.out_dir = args.dir;
    opt.threads = args.threads;
    opt.progress = !args.quiet && speaks;
    opt.write_fields = opt.resume->info.write_fields;
    opt.comm = comm;
    if (!args.quiet && speaks)
      std::cerr << fmt::format("pdmpm: resuming {} after step {} in {}\n", scene.id, opt.resume->info.step, args.dir);
    return run_and_report(scene, opt, args.quiet, speaks);
  } catch (...) {
    return report_error(comm);
  }
}

}  // namespace pdmpm::app
