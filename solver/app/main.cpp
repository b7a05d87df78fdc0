// The pdmpm command line: run scenes, print bond constants.
#include <CLI/CLI.hpp>

#include <iostream>

#include "solver/app/commands.hpp"
#include "solver/core/build_info.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/dist/launch.hpp"

int main(int argc, char** argv) {
  CLI::App app{"pdmpm — peridynamics and material point method reference solver"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("pdmpm ") + pdmpm::build_info::git_sha());

  pdmpm::app::RunArgs run;
  auto* cmd_run = app.add_subcommand("run", "Run a scene: writes fields.h5/.xdmf, history.csv, summary.json in --out");
  cmd_run->add_option("scene", run.scene, "Scene file (TOML)")->required();
  cmd_run->add_option("--out,-o", run.out, "Output directory (default: out/<scene id>)");
  cmd_run->add_option("--threads,-t", run.threads, "OpenMP threads (default: all)")->check(CLI::Range(1, 1024));
  cmd_run->add_flag("--quiet,-q", run.quiet, "No progress output");
  cmd_run->add_flag("--no-fields", run.no_fields, "Skip fields.h5/.xdmf (history and summary only)");
  cmd_run->add_option("--checkpoint-every", run.checkpoint_every,
                      "Write DIR/checkpoint.pdmpm every N steps (\"5000\") or wall time (\"90s\", \"30m\", \"2h\"); "
                      "SIGINT/SIGTERM always write one and exit with status 5");
  cmd_run
      ->add_option("--stop-after", run.stop_after,
                   "Stop after this step as a SIGINT would (checkpoint written, exit status 5): a run split into jobs")
      ->check(CLI::PositiveNumber);

  pdmpm::app::ResumeArgs resume;
  auto* cmd_resume = app.add_subcommand(
      "resume", "Continue an interrupted run from DIR/checkpoint.pdmpm; the outputs are those of an uninterrupted run");
  cmd_resume->add_option("dir", resume.dir, "Output directory of the interrupted run")->required();
  cmd_resume->add_option("--threads,-t", resume.threads, "OpenMP threads (default: all; results do not depend on it)")
      ->check(CLI::Range(1, 1024));
  cmd_resume->add_flag("--quiet,-q", resume.quiet, "No progress output");
  cmd_resume->add_option("--checkpoint-every", resume.checkpoint_every, "As for run");

  pdmpm::app::CheckArgs check;
  auto* cmd_check = app.add_subcommand(
      "check",
      "Validate a scene and print what a run would be: method, particles, bonds, memory, steps, and the "
      "wall time estimated from a few calibration steps (nothing written)");
  cmd_check->add_option("scene", check.scene, "Scene file (TOML)")->required();
  cmd_check->add_option("--threads,-t", check.threads, "OpenMP threads (default: all)")->check(CLI::Range(1, 1024));
  cmd_check
      ->add_option("--calibration-seconds", check.calibration_seconds,
                   "About how long to time steps for the estimate (default 1; 0: validate and describe only)")
      ->check(CLI::Range(0.0, 3600.0));

  pdmpm::app::ConstantsArgs cst;
  auto* cmd_const = app.add_subcommand(
      "constants", "Print the bond constants of docs/models/pmb.md and docs/models/lps.md for a material and horizon");
  cmd_const->add_option("--E", cst.E, "Young's modulus (Pa)")->check(CLI::PositiveNumber);
  cmd_const->add_option("--nu", cst.nu, "Poisson's ratio")->check(CLI::Range(-0.999, 0.4999));
  cmd_const->add_option("--delta", cst.delta, "Horizon δ (m)")->check(CLI::PositiveNumber);
  cmd_const->add_option("--thickness", cst.thickness, "Plate thickness h for 2D (m)")->check(CLI::PositiveNumber);
  cmd_const->add_option("--area", cst.area, "Bar cross-section A for 1D (m²)")->check(CLI::PositiveNumber);
  cmd_const->add_option("--G0", cst.G0, "Fracture energy G₀ for the critical stretch (J/m²)")
      ->check(CLI::PositiveNumber);
  cmd_const->add_option("--format", cst.format, "Output format")->check(CLI::IsMember({"table", "json"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  // Under mpirun (several processes) a run or resume is distributed
  // (docs/models/distributed.md); check works on one process.
  if (const auto launch = pdmpm::dist::launch_from_environment(); launch.processes > 1) {
    if (*cmd_run || *cmd_resume) {
      const pdmpm::dist::MpiSession session(argc, argv);
      const pdmpm::dist::Communicator comm;
      return *cmd_run ? pdmpm::app::run_command(run, &comm) : pdmpm::app::resume_command(resume, &comm);
    }
    if (*cmd_check) {
      if (launch.rank == 0)
        std::cerr << "error: pdmpm was started as " << launch.processes << " processes (mpirun): check runs on "
                  << "one process; start check without mpirun\n";
      return 2;
    }
  }
  if (*cmd_run) return pdmpm::app::run_command(run);
  if (*cmd_resume) return pdmpm::app::resume_command(resume);
  if (*cmd_check) return pdmpm::app::check_command(check);
  if (*cmd_const) return pdmpm::app::constants_command(cst);
  return 2;
}
