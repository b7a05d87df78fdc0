#pragma once
// The subcommands of pdmpm. Each returns the process exit status:
// 0 success, 2 bad input (nothing written), 3 run failed (unstable, not converged),
// 4 internal error, 5 interrupted by SIGINT/SIGTERM (checkpoint written where the run has one).
#include <cstdint>
#include <string>

namespace pdmpm::dist {
class Communicator;
}

namespace pdmpm::app {

struct RunArgs {
  std::string scene, out;
  int threads = 0;
  bool quiet = false, no_fields = false;
  std::string checkpoint_every;  // steps ("5000") or wall time ("30m"); empty: none
  std::int64_t stop_after = 0;   // stop after this step as an interrupt would; 0: run to the end
};
// `comm`: the processes of a distributed run (mpirun); process 0 writes and speaks.
int run_command(const RunArgs& args, const dist::Communicator* comm = nullptr);

struct ResumeArgs {
  std::string dir;
  int threads = 0;
  bool quiet = false;
  std::string checkpoint_every;
};
int resume_command(const ResumeArgs& args, const dist::Communicator* comm = nullptr);

struct CheckArgs {
  std::string scene;
  int threads = 0;
  double calibration_seconds = 1.0;  // steps timed for the estimate; 0: validate and describe only
};
int check_command(const CheckArgs& args);

struct ConstantsArgs {
  double E = 200e9, nu = 0.25, delta = 3.015e-3, thickness = 1e-3, area = 1e-6, G0 = 0.0;
  std::string format = "table";
};
int constants_command(const ConstantsArgs& args);

}  // namespace pdmpm::app
