// Distributed PD throughput (docs/models/distributed.md): an LPS block stepped with
// velocity Verlet on however many processes mpirun starts, timed between barriers.
// Strong scaling: the same block for any process count; weak (--weak): the block
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

}  // namespace
}  // namespace pdmpm

int main(int argc, char** argv) {
  using namespace pdmpm;
  dist::MpiSession session(argc, argv);
  const dist::Communicator comm;
  CLI::App app{"distributed LPS throughput"};
  int n = 40, steps = 50;
  bool weak = false;
  app.add_option("--n", n, "block edge in particles (n³; weak: n³ per process)");
  app.add_option("--steps", steps, "time steps timed");
  app.add_flag("--weak", weak, "grow the block along x with the process count");
  CLI11_PARSE(app, argc, argv);
  try {
    const int nx = weak ? n * comm.size() : n;
    const auto scene = io::parse_scene_text(block_scene(nx, n, n), "mpi_scaling");
    auto setup = sim::build_pd<3>(scene, &comm);
    auto& p = setup.system.particles;
    for (Index i = 0; i < p.n_real; ++i) p.v[i] = Vec<3>(1.0 * p.x0[i][0], -0.5 * p.x0[i][1], 0.0) * 100.0;
    const double dt = comm.min(0.7 * time::silling_askari_step<3>(setup.system, *setup.model, 0.0));
    auto st = sim::make_simulation(setup);
    time::VelocityVerlet<3> stepper(st, dt);
    stepper.start();
    comm.barrier();
    const double t0 = MPI_Wtime();
    for (int k = 0; k < steps; ++k) stepper.step(false);
    comm.barrier();
    const double seconds = MPI_Wtime() - t0;
    const std::int64_t particles = comm.sum(p.n_real);
    const std::int64_t halo = comm.sum(p.n_ghost());
    const double largest_halo = comm.max(static_cast<double>(p.n_ghost()) / static_cast<double>(p.n_real));
    const std::int64_t sent = setup.ownership ? comm.sum(setup.ownership->values_sent) : 0;
    if (comm.rank() == 0) {
      nlohmann::json j = {{"processes", comm.size()},
                          {"threads_per_process", omp_get_max_threads()},
                          {"scaling", weak ? "weak" : "strong"},
                          {"particles", particles},
                          {"halo_particles", halo},
                          {"largest_halo_over_own", largest_halo},
                          {"values_sent_per_exchanged_scalar", sent},
                          {"steps", steps},
                          {"seconds", seconds},
                          {"particle_steps_per_second", static_cast<double>(particles) * steps / seconds}};
      std::cout << j.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "rank " << comm.rank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  return 0;
}
