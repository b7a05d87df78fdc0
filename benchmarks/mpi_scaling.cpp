// Distributed throughput (docs/models/distributed.md): an LPS block stepped with
// velocity Verlet (--method lps), or an MPM plate (--method mpm: 2D plane stress, uGIMP,
// MUSL, J2, pulled at its ends), on however many processes mpirun starts, timed between
// barriers. Strong scaling: the same body for any process count; weak (--weak): the body
// grows along x with the process count. Prints one JSON line (rank 0). Run by
// ci/mpi_scaling.sh, not in CI: timings are not tests.
#include <mpi.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/dist/communicator.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/stable_step.hpp"
#include "solver/time/velocity_verlet.hpp"

namespace pdmpm {
namespace {

std::string block_scene(int nx, int ny, int nz) {
  const auto mm = [](int n) { return std::to_string(n * 1e-3); };
  return "[scene]\nid = \"mpi_scaling\"\n[discretization]\ndimension = 3\nspacing = 1e-3\nhorizon_ratio = 3.015\n"
         "[[shape]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [" +
      mm(nx) + ", " + mm(ny) + ", " + mm(nz) +
      "]\n[material]\ndensity = 7850\nyoungs_modulus = 200e9\npoissons_ratio = 0.3\n"
      "[model]\ntype = \"lps\"\n[time]\nsteps = 1\n";
}

// nx × ny points, Δx = 0.5 mm, the central crack's J2 steel, ends pulled at ±5 m/s.
std::string plate_scene(int nx, int ny) {
  const auto mm = [](int n) { return std::to_string(n * 0.5e-3); };
  return "[scene]\nid = \"mpi_scaling_mpm\"\n[discretization]\ndimension = 2\nplane = \"stress\"\nspacing = 0.5e-3\n"
         "thickness = 1e-3\n[[shape]]\ntype = \"box\"\nmin = [0, 0]\nmax = [" +
      mm(nx) + ", " + mm(ny) +
      "]\n[material]\nconstitutive = \"j2\"\ndensity = 7850\nyoungs_modulus = 200e9\npoissons_ratio = 0.3\n"
      "yield_stress = 300e6\ntangent_modulus = 2e9\n[model]\ntype = \"mpm\"\n[time]\nsteps = 1\n"
      "[[boundary]]\nname = \"left\"\nkind = \"velocity\"\nregion = { type = \"box\", min = [-1, -1], max = [1e-3, 1] "
      "}\n"
      "value = [\"-5\", \"free\"]\n[[boundary]]\nname = \"right\"\nkind = \"velocity\"\nregion = { type = \"box\", "
      "min = [" +
      std::to_string(nx * 0.5e-3 - 1e-3) + ", -1], max = [1, 1] }\nvalue = [\"5\", \"free\"]\n";
}

struct Measured {
  double seconds = 0.0;
  std::int64_t particles = 0, halo = 0, sent = 0;
  double largest_halo = 0.0;
};

// Wall seconds of `steps` calls of step() on every process, between barriers; the counts of
// own and halo particles (MPM: ghosts) over the processes.
template <class Step>
Measured timed(const dist::Communicator& comm, int steps, Step&& step, Index own, Index halo) {
  comm.barrier();
  const double t0 = MPI_Wtime();
  for (int k = 0; k < steps; ++k) step();
  comm.barrier();
  Measured m;
  m.seconds = MPI_Wtime() - t0;
  m.particles = comm.sum(own);
  m.halo = comm.sum(halo);
  m.largest_halo = comm.max(static_cast<double>(halo) / static_cast<double>(own));
  return m;
}

Measured run_lps(const dist::Communicator& comm, int nx, int n, int steps) {
  const auto scene = io::parse_scene_text(block_scene(nx, n, n), "mpi_scaling");
  auto setup = sim::build_pd<3>(scene, &comm);
  auto& p = setup.system.particles;
  for (Index i = 0; i < p.n_real; ++i) p.v[i] = Vec<3>(1.0 * p.x0[i][0], -0.5 * p.x0[i][1], 0.0) * 100.0;
  const double dt = comm.min(0.7 * time::silling_askari_step<3>(setup.system, *setup.model, 0.0));
  auto st = sim::make_simulation(setup);
  time::VelocityVerlet<3> stepper(st, dt);
  stepper.start();
  Measured m = timed(
      comm, steps, [&] { stepper.step(false); }, p.n_real, p.n_ghost());
  m.sent = setup.ownership ? comm.sum(setup.ownership->values_sent) : 0;
  return m;
}

Measured run_mpm(const dist::Communicator& comm, int nx, int n, int steps) {
  const auto scene = io::parse_scene_text(plate_scene(nx, n), "mpi_scaling_mpm");
  auto setup = sim::build_mpm<2>(scene, &comm);
  mpm::Simulation<2> sim(setup.settings, setup.particles, scene.file, "mpm", setup.others);
  const double dt = 0.5 * sim.stable_dt();
  for (int k = 0; k < 5; ++k) sim.step(dt);  // the grips start the body moving
  return timed(
      comm, steps, [&] { sim.step(dt); }, setup.particles.n_real, sim.ghost_points());
}

}  // namespace
}  // namespace pdmpm

int main(int argc, char** argv) {
  using namespace pdmpm;
  dist::MpiSession session(argc, argv);
  const dist::Communicator comm;
  CLI::App app{"distributed LPS and MPM throughput"};
  int n = 0, steps = 50;
  bool weak = false;
  std::string method = "lps";
  app.add_option("--method", method, "lps (3D block) or mpm (2D plate)")->check(CLI::IsMember({"lps", "mpm"}));
  app.add_option("--n", n, "body edge in particles (lps: n³, default 40; mpm: n², default 200; weak: per process)");
  app.add_option("--steps", steps, "time steps timed");
  app.add_flag("--weak", weak, "grow the body along x with the process count");
  CLI11_PARSE(app, argc, argv);
  try {
    if (n <= 0) n = method == "lps" ? 40 : 200;
    const int nx = weak ? n * comm.size() : n;
    const Measured m = method == "lps" ? run_lps(comm, nx, n, steps) : run_mpm(comm, nx, n, steps);
    if (comm.rank() == 0) {
      nlohmann::json j = {{"method", method},
                          {"processes", comm.size()},
                          {"threads_per_process", omp_get_max_threads()},
                          {"scaling", weak ? "weak" : "strong"},
                          {"particles", m.particles},
                          {"halo_particles", m.halo},
                          {"largest_halo_over_own", m.largest_halo},
                          {"values_sent_per_exchanged_scalar", m.sent},
                          {"steps", steps},
                          {"seconds", m.seconds},
                          {"particle_steps_per_second", static_cast<double>(m.particles) * steps / m.seconds}};
      std::cout << j.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "rank " << comm.rank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  return 0;
}
