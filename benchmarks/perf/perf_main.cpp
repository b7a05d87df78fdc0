// pdmpm_perf: the performance driver of issue 6, in one process run —
//   memory per bond (memory_per_bond.hpp), the force kernels' thread scaling and
//   roofline (kernel_scaling.hpp), the cost of plasticity (plastic_cost.hpp), of the stabilized
//   hybrid PD model (hpd_cost.hpp), the MPM step against PD (mpm_step.hpp), and pdmpm next to LAMMPS' peri/pmb and peri/lps
//   (lammps_side_by_side.hpp).
// Raw results: <results>/bench/perf/*.json; targets: gates of the report's
// "performance" problem; plots and tables: <results>/data/performance/.
// Timing targets are benchmarks, not unit tests: nothing here runs under ctest.
// Exit status: 0 when it ran (targets may FAIL; the report shows them), 1 on an error.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <omp.h>

#include <fstream>
#include <string>

#include "benchmarks/perf/kernel_scaling.hpp"
#include "benchmarks/perf/lammps_side_by_side.hpp"
#include "benchmarks/perf/memory_per_bond.hpp"
#include "benchmarks/perf/perf_evidence.hpp"
#include "benchmarks/perf/perf_output.hpp"
#include "benchmarks/perf/mpm_step.hpp"
#include "benchmarks/perf/hpd_cost.hpp"
#include "benchmarks/perf/plastic_cost.hpp"
#include "solver/pd/kernels/bond_kernels.hpp"
#include "verification/support/provenance.hpp"

namespace {

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pdmpm::perf;
  Options o;
  std::string parts = "memory,kernels,plastic,hpd,mpm,lammps";
  CLI::App app{"pdmpm performance driver (issue 6): memory per bond, kernel scaling and roofline, LAMMPS side by side"};
  app.add_option("--refine", o.refine, "problem size: lattice refinement of LAMMPS' example target (3: 1e7 bond sides)")
      ->check(CLI::Range(1, 8));
  app.add_option("--reps", o.reps, "interleaved repetitions of every timing")->check(CLI::Range(1, 100));
  app.add_option("--steps", o.steps, "time steps per LAMMPS-comparison repetition")->check(CLI::Range(1, 100000));
  app.add_option("--mpm-warmup", o.mpm_warmup,
                 "steps of the MPM-step bodies before their samples, which all start there")
      ->check(CLI::Range(0, 100000));
  app.add_option("--kernel-calls", o.kernel_calls, "force evaluations per kernel timing sample")
      ->check(CLI::Range(1, 1000));
  app.add_option("--parts", parts, "comma-separated subset of memory,kernels,plastic,hpd,mpm,lammps");
  CLI11_PARSE(app, argc, argv);
  o.results = pdmpm::test::results_dir();
  o.parts.clear();
  for (std::size_t a = 0, b; a <= parts.size(); a = b + 1) {
    b = parts.find(',', a);
    if (b == std::string::npos) b = parts.size();
    const std::string p = parts.substr(a, b - a);
    if (p != "memory" && p != "kernels" && p != "plastic" && p != "hpd" && p != "mpm" && p != "lammps") {
      fmt::print(stderr, "pdmpm_perf: --parts: unknown part \"{}\" (memory, kernels, plastic, hpd, mpm, lammps)\n", p);
      return 2;
    }
    o.parts.insert(p);
  }

  try {
    nlohmann::json context = pdmpm::test::provenance();
    context["simd"] = pdmpm::pd::kernels::simd_level();
    context["cores"] = omp_get_num_procs();
    context["load_average_start"] = load_average();
    context["options"] = {{"refine", o.refine},
                          {"reps", o.reps},
                          {"steps", o.steps},
                          {"mpm_warmup", o.mpm_warmup},
                          {"kernel_calls", o.kernel_calls},
                          {"parts", parts}};
    fmt::print("pdmpm_perf: results in {}/bench/perf (load average {})\n", o.results.string(), load_average());
    Collected c;
    // Memory first, while the process is small and nothing else is allocated.
    if (o.parts.count("memory")) {
      c.memory.push_back(memory_per_bond("pmb", true));
      c.memory.push_back(memory_per_bond("lps", false));
      write_result("memory", c.memory);
    }
    if (o.parts.count("kernels")) {
      c.kernels = kernel_scaling(o);
      write_result("kernels", c.kernels);
    }
    if (o.parts.count("plastic")) write_result("plastic", plastic_cost(o));
    if (o.parts.count("hpd")) write_result("hpd", hpd_cost(o));
    if (o.parts.count("mpm")) write_result("mpm", mpm_step(o));
    if (o.parts.count("lammps")) {
      c.lammps.push_back(lammps_side_by_side("pmb", o));
      c.lammps.push_back(lammps_side_by_side("lps", o));
      write_result("lammps", c.lammps);
    }
    context["load_average_end"] = load_average();
    c.context = context;
    write_result("context", context);
    record_evidence(c);
    fmt::print("pdmpm_perf: done (load average {})\n", load_average());
  } catch (const std::exception& e) {
    fmt::print(stderr, "pdmpm_perf: {}\n", e.what());
    return 1;
  }
  return 0;
}
