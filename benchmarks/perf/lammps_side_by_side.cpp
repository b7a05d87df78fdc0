#include "benchmarks/perf/lammps_side_by_side.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "benchmarks/perf/perf_output.hpp"
#include "benchmarks/perf/perf_problem.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/sim/pd_setup.hpp"
#include "verification/support/lammps.hpp"

namespace pdmpm::perf {
namespace {

using nlohmann::json;

struct OurRun {
  double kernel = 0.0, contact = 0.0, loop = 0.0;  // seconds over the time steps
  std::vector<Vec<3>> u;
};

// A fresh set-up every repetition (as LAMMPS starts afresh), one OpenMP thread.
OurRun run_ours(const io::Scene& scene, std::int64_t steps, double dt) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  auto setup = sim::build_pd<3>(scene);
  auto state = sim::make_simulation(setup);
  time::VelocityVerlet<3> stepper(state, dt);
  stepper.start();  // the first force evaluation: outside the timing, as LAMMPS' set-up
  const double k0 = state.force_seconds(), c0 = state.contact_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  for (std::int64_t s = 0; s < steps; ++s) stepper.step(false);
  OurRun r;
  r.loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.kernel = state.force_seconds() - k0;
  r.contact = state.contact_seconds() - c0;
  const auto& p = setup.system.particles;
  r.u.assign(p.u.begin(), p.u.begin() + p.n_real);
  omp_set_num_threads(before);
  return r;
}

// max |u_pdmpm − u_LAMMPS| / max |u_LAMMPS| over all particles.
double displacement_difference(const sim::PdSetup<3>& setup, const OurRun& ours, const test::lammps::Frame& last) {
  const auto& p = setup.system.particles;
  double du = 0.0, umax = 0.0;
  for (Index i = 0; i < p.n_real; ++i) {
    Vec<3> ul;
    for (int a = 0; a < 3; ++a) ul[a] = last.x[i][a] - p.x0[i][a];
    du = std::max(du, (ours.u[i] - ul).norm());
    umax = std::max(umax, ul.norm());
  }
  return umax > 0.0 ? du / umax : 1.0;  // nothing moved: the check cannot pass
}

}  // namespace

json lammps_side_by_side(const std::string& model, const Options& o) {
  const std::string style = "peri/" + model;
  fmt::print("LAMMPS side by side: {} (refine {}, {} steps, {} repetitions)\n", style, o.refine, o.steps, o.reps);
  if (!test::lammps::available()) {
    fmt::print("  LAMMPS (`{}`) is not on PATH: skipped (ci/install_deps.sh installs Debian's lammps)\n",
               test::lammps::executable());
    return {{"model", model}, {"skipped", "lmp not found"}};
  }
  const io::Scene scene = perf_scene(model, o.refine);
  const auto reference = sim::build_pd<3>(scene);  // the particles LAMMPS is given
  const double dt = perf_dt(o.refine);
  const double sides = static_cast<double>(reference.system.families.n_bonds());
  test::lammps::Options lo;
  lo.work_dir = o.results / "work" / "perf" / model;
  lo.steps = o.steps;
  lo.dt = dt;
  lo.threads = 1;

  std::vector<double> kernel, contact, ours_pair, ours_loop, lmp_pair, lmp_loop, lmp_compute;
  test::lammps::Result lmp;
  OurRun ours;
  for (int k = 0; k < o.reps; ++k) {
    ours = run_ours(scene, o.steps, dt);
    lmp = test::lammps::run(scene, reference, lo);
    kernel.push_back(ours.kernel);
    contact.push_back(ours.contact);
    ours_pair.push_back(ours.kernel + ours.contact);
    ours_loop.push_back(ours.loop);
    lmp_pair.push_back(lmp.sections["Pair"]);
    lmp_loop.push_back(lmp.loop_seconds);
    lmp_compute.push_back(lmp.loop_seconds - lmp.sections["Output"]);  // the last step's dump is output
    fmt::print("  rep {}: pdmpm force {:.3f} s (kernel {:.3f} + contact {:.3f}), LAMMPS Pair {:.3f} s\n", k + 1,
               ours_pair.back(), ours.kernel, ours.contact, lmp_pair.back());
  }
  const double evals = sides * static_cast<double>(o.steps);  // bond sides × steps
  const Ratio speedup = ratio_of_medians(lmp_pair, ours_pair);
  const Ratio speedup_kernel = ratio_of_medians(lmp_pair, kernel);
  const Ratio speedup_loop = ratio_of_medians(lmp_compute, ours_loop);
  const double agree = lmp.frames.empty() ? 1.0 : displacement_difference(reference, ours, lmp.frames.back());
  const double ours_rate = evals / median(ours_pair), lmp_rate = evals / median(lmp_pair);

  const std::string size = fmt::format("{} particles, {:.3g} bond sides", reference.system.n_real(), sides);
  target({.id = "performance.lammps_" + model + ".speedup",
          .claim = fmt::format(
              "pdmpm's force evaluation ({}: bond kernel + short-range contact) shall do at least 5× the bond "
              "evaluations per second per core of LAMMPS {} (its Pair time) on the same 3D problem ({})",
              model == "pmb" ? "PMB" : "LPS, ω = 1/|ξ|", style, size),
          .measured = speedup.value,
          .expected = 5.0,
          .tolerance = 0.0,
          .compare = test::Compare::at_least,
          .tolerance_reason = fmt::format(
              "a target, not a tolerance (issue 6). Ratio of medians of {} interleaved repetitions of {} steps "
              "in one process run, one core each; bootstrap 95 % interval [{:.3g}, {:.3g}]",
              o.reps, o.steps, speedup.lo, speedup.hi),
          .source =
              "[pdmpm] docs/design.md (performance targets); [parks2008]; LAMMPS src/PERI/pair_peri_" + model + ".cpp",
          .unit = "×",
          .problem = problem});
  target({.id = "performance.lammps_" + model + ".displacement",
          .claim = fmt::format(
              "in the timed runs, the displacement fields of pdmpm and LAMMPS {} shall agree at every particle "
              "to 1e-6 of the largest displacement after {} steps",
              style, o.steps),
          .measured = agree,
          .expected = 1e-6,
          .tolerance = 0.0,
          .compare = test::Compare::at_most,
          .tolerance_reason =
              "same model, partial volumes, contact rule, indenter law and integrator: only round-off differs (as the "
              "elastic LAMMPS gate, lammps_comparison_gate.cpp)",
          .source = "[parks2008]; [thompson2022]; verification/support/lammps.hpp",
          .unit = "",
          .problem = problem});

  return {{"model", model},
          {"lammps_style", style},
          {"lammps_version", lmp.version},
          {"refine", o.refine},
          {"particles", reference.system.n_real()},
          {"bond_sides", sides},
          {"lammps_bond_sides", lmp.bonds},
          {"steps", o.steps},
          {"dt", dt},
          {"reps", o.reps},
          {"threads", 1},
          {"bond_evaluations_per_rep", evals},
          {"pdmpm", {{"force_s", ours_pair}, {"kernel_s", kernel}, {"contact_s", contact}, {"loop_s", ours_loop}}},
          {"lammps",
           {{"pair_s", lmp_pair},
            {"loop_s", lmp_loop},
            {"loop_minus_output_s", lmp_compute},
            {"sections_last_rep", lmp.sections},
            {"memory_mbytes_estimate", lmp.memory_mbytes}}},
          {"bond_evals_per_s_per_core",
           {{"pdmpm", ours_rate}, {"pdmpm_kernel_only", evals / median(kernel)}, {"lammps", lmp_rate}}},
          {"speedup_force_vs_pair", to_json(speedup)},
          {"speedup_kernel_vs_pair", to_json(speedup_kernel)},
          {"speedup_steps_vs_loop", to_json(speedup_loop)},
          {"max_rel_displacement_difference", agree}};
}

}  // namespace pdmpm::perf
