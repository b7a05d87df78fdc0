// Rank invariance: a distributed PD run (solver/dist/) gives the one-process run's
// answer to the bit. Each case is a plate (2D) or block (3D) whose two halves are
// pulled apart by their initial velocities (±5 m/s: the release wave's strain,
// v/c ≈ 1e-3, breaks bonds where the halves meet and where waves cross, not
// everywhere), so cracks cross process boundaries while the rest still carries
// stress at the end — a run that shattered to force-free fragments would hide a
// wrong halo state. Every process runs its share;
// rank 0 also runs the whole body alone and compares displacements, velocities,
// forces, every bond's flags and damage. The MPM cases (J2 with ductile failure, grips
// at full speed from t = 0) compare every point's u, v, F, τ, ε̄_p and failure flag, the
// energies, momentum, mass, reactions and the balance's pending boundary work.
// Run under mpirun with any process count (ctest: 2, 3 and 4); writes one gate per case
// and a table for the report.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "solver/dist/communicator.hpp"
#include "solver/io/scene.hpp"
#include "solver/pd/damage.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/stable_step.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;

// 48 × 24 (2D) or 16 × 10 × 8 (3D) particles, Δx = 1 mm, s₀ = 1e-3.
std::string scene_text(const std::string& model, int D) {
  std::string s = "[scene]\nid = \"ranks\"\n[discretization]\ndimension = " + std::to_string(D) +
      "\nspacing = 1e-3\nhorizon_ratio = 3.015\n";
  if (D == 2)
    s += "plane = \"stress\"\nthickness = 1e-3\n[[shape]]\ntype = \"box\"\nmin = [0, 0]\nmax = [0.048, 0.024]\n";
  else
    s += "[[shape]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [0.016, 0.010, 0.008]\n";
  s += "[material]\ndensity = 7850\nyoungs_modulus = 200e9\ncritical_stretch = 1e-3\n";
  if (!pd::model_info(model).pair_potential)
    s += "poissons_ratio = 0.3\n";  // not ¼: there the 3D dilatation term vanishes (A = 3K − 5μ = 0)
  s += "[model]\ntype = \"" + model + "\"\n[time]\nsteps = 1\n";
  // Both ends keep pulling (held components: the supports' work is booked as well).
  const auto strip = [&](const std::string& name, const std::string& lo, const std::string& hi, double vx) {
    const std::string free = D == 2 ? ", \"free\"" : ", \"free\", \"free\"";
    s += "[[boundary]]\nname = \"" + name + "\"\nkind = \"velocity\"\nregion = { type = \"box\", min = " + lo +
        ", max = " + hi + " }\nvalue = [" + std::to_string(vx) + free + "]\n";
  };
  if (D == 2) {
    strip("left", "[-1, -1]", "[0.002, 1]", -5.0);
    strip("right", "[0.046, -1]", "[1, 1]", 5.0);
  } else {
    strip("left", "[-1, -1, -1]", "[0.002, 1, 1]", -5.0);
    strip("right", "[0.014, -1, -1]", "[1, 1, 1]", 5.0);
  }
  return s;
}

struct Fields {
  std::vector<double> u, v, f, damage;
  std::vector<std::int64_t> flags;
  std::int64_t broken_across = 0;            // broken bond sides whose other end a different process owns
  double largest_force = 0.0;                // max |f| component at the end (the body still carries stress)
  std::int64_t halo = 0, own = 0, sent = 0;  // this process's halo and own particles, values it sends per scalar
  // Sums over the body at the end: kinetic and strain energy, external work, pending
  // work, linear and angular momentum.
  std::vector<double> sums;
};

// A bitwise-identity gate: `measured` values differ in any bit, plus one for each `unfit` reason
// the case gives (it would not test the claim), each printed.
test::Gate identity_gate(const std::string& id, const std::string& claim, std::size_t measured,
                         const std::string& reason, const std::vector<std::string>& unfit) {
  test::Gate g{.id = id,
               .claim = claim + " (measured: values that differ in any bit)",
               .measured = static_cast<double>(measured + unfit.size()),
               .expected = 0.0,
               .tolerance = 0.0,
               .compare = test::Compare::abs,
               .tolerance_reason = "Bitwise identity is the claim: " + reason,
               .source = "[pdmpm] docs/models/distributed.md",
               .unit = "",
               .problem = "distributed"};
  for (const auto& why : unfit) std::cerr << id << ": " << why << "\n";
  return g;
}

template <int D>
Fields run(const io::Scene& scene, const dist::Communicator* comm, double& dt, int steps) {
  auto setup = sim::build_pd<D>(scene, comm);
  auto& p = setup.system.particles;
  const double half = 0.5 * (D == 2 ? 0.048 : 0.016);
  for (Index i = 0; i < p.n_real; ++i) p.v[i][0] = p.x0[i][0] < half ? -5.0 : 5.0;
  if (dt <= 0.0) dt = 0.7 * time::silling_askari_step<D>(setup.system, *setup.model, 0.0);
  auto st = sim::make_simulation(setup);
  time::VelocityVerlet<D> stepper(st, dt);
  stepper.start();
  for (int k = 1; k <= steps; ++k) stepper.step(k == steps);

  Fields out;
  out.sums = {st.kinetic_energy(), st.internal_energy(), stepper.external_work(), stepper.absolute_work(),
              stepper.pending_work()};
  for (int a = 0; a < D; ++a) out.sums.push_back(st.momentum()[a]);
  for (int a = 0; a < 3; ++a) out.sums.push_back(st.angular_momentum()[a]);
  const auto n = static_cast<std::size_t>(p.n_real) * D;
  out.u.assign(p.u.data()->data(), p.u.data()->data() + n);
  out.v.assign(p.v.data()->data(), p.v.data()->data() + n);
  out.f.assign(p.f.data()->data(), p.f.data()->data() + n);
  out.damage = pd::local_damage(setup.system);
  if (setup.ownership) {
    out.halo = static_cast<std::int64_t>(setup.ownership->halo.size());
    out.own = setup.ownership->own.size();
    out.sent = setup.ownership->values_sent;
  }
  for (const double x : out.f) out.largest_force = std::max(out.largest_force, std::abs(x));
  const auto& fam = setup.system.families;
  for (BondIndex b = 0; b < fam.n_bonds(); ++b) {
    out.flags.push_back(setup.system.bonds.flags.trial[b]);
    out.broken_across += setup.system.bonds.broken(b) && fam.neighbor[b] >= p.n_real;
  }
  return out;
}

std::size_t differing(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(double)) != 0;
  return n;
}

template <int D>
bool check(const std::string& model, const dist::Communicator& comm, json& rows) {
  const auto scene = io::parse_scene_text(scene_text(model, D), "ranks");
  // hpd's 3D step costs ~100 ms on one thread (its sub-horizon fits): fewer steps, still
  // past the first bonds broken across processes.
  const int steps = D == 2 ? 400 : model == "hpd" ? 60 : 250;
  Fields one;
  double dt = 0.0;
  if (comm.rank() == 0) one = run<D>(scene, nullptr, dt, steps);
  dt = comm.min(comm.rank() == 0 ? dt : std::numeric_limits<double>::infinity());
  const auto many = run<D>(scene, &comm, dt, steps);
  const auto u = comm.gather(many.u), v = comm.gather(many.v), f = comm.gather(many.f),
             damage = comm.gather(many.damage);
  const auto flags = comm.gather(many.flags);
  const std::int64_t across = comm.sum(many.broken_across), halo = comm.sum(many.halo), sent = comm.sum(many.sent);
  // The largest halo relative to its process's own particles (what a ghost layer costs).
  const double halo_share =
      comm.max(many.own > 0 ? static_cast<double>(many.halo) / static_cast<double>(many.own) : 0.0);
  if (comm.rank() != 0) return true;

  std::size_t dflags = flags.size() == one.flags.size() ? 0 : std::max(flags.size(), one.flags.size());
  for (std::size_t b = 0; dflags == 0 && b < flags.size(); ++b) dflags += flags[b] != one.flags[b];
  // Every process holds the same totals; rank 0's are compared.
  const std::size_t dsums = differing(one.sums, many.sums);
  const std::size_t du = differing(one.u, u), dv = differing(one.v, v), df = differing(one.f, f),
                    dd = differing(one.damage, damage);
  std::int64_t broken = 0;
  for (const auto fl : one.flags) broken += (fl & pd::kBondBroken) != 0;
  const std::string dim = std::to_string(D) + "d", ranks = std::to_string(comm.size());
  // A case that would not test the claim fails: a crack that stays inside one process,
  // or a body left without stress (a wrong halo state would leave no trace).
  std::vector<std::string> unfit;
  if (comm.size() > 1 && across == 0) unfit.push_back("no broken bond crosses a process boundary");
  if (!(one.largest_force > 0.0) || broken == 0) unfit.push_back("nothing broke, or no force is left at the end");
  const test::Gate g = identity_gate(
      "distributed." + model + "." + dim + "." + ranks + "_ranks",
      "A fracturing " + dim + " body (" + model + ", " + std::to_string(steps) + " steps, " +
          std::to_string(broken / 2) + " bonds broken, " + std::to_string(across / 2) +
          " of them across process boundaries) shall give bitwise identical displacements, velocities, forces, bond "
          "flags, damage, energies, work and momenta on " +
          ranks + " processes as on one",
      du + dv + df + dd + dflags + dsums,
      "each process builds its particles' families by the same lattice offsets, the halo brings it its neighbours' "
      "exact state, and every force is gathered per particle in the same order, so no rounding may depend on the "
      "process count.",
      unfit);
  const bool ok = test::write_gate(g, "rank_invariance");
  rows.push_back({model, dim, comm.size(), static_cast<double>(one.damage.size()), halo, halo_share, sent, steps,
                  broken / 2, across / 2, static_cast<double>(du), static_cast<double>(dv), static_cast<double>(df),
                  static_cast<double>(dflags), static_cast<double>(dd), static_cast<double>(dsums)});
  std::cout << (ok ? "PASS " : "FAIL ") << g.id << ": " << g.measured << " values differ, " << across / 2
            << " broken bonds across processes\n";
  return ok;
}

// MPM: a notched plate (2D plane stress, 48 × 24) or block (3D, 16 × 10 × 8) of J2 steel
// with ductile failure, its ends pulled apart at ±10 m/s from t = 0 on the grid.
std::string mpm_scene_text(int D, const std::string& scheme) {
  std::string s =
      "[scene]\nid = \"ranks_mpm\"\n[discretization]\ndimension = " + std::to_string(D) + "\nspacing = 1e-3\n";
  if (D == 2)
    s += "plane = \"stress\"\nthickness = 1e-3\n[[shape]]\ntype = \"box\"\nmin = [0, 0]\nmax = [0.048, 0.024]\n"
         "[[shape]]\ntype = \"circle\"\ncenter = [0.024, 0.0]\nradius = 4e-3\noperation = \"subtract\"\n";
  else
    s += "[[shape]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [0.016, 0.010, 0.008]\n";
  s += "[material]\nconstitutive = \"j2\"\ndensity = 7850\nyoungs_modulus = 200e9\npoissons_ratio = 0.3\n"
       "yield_stress = 250e6\ntangent_modulus = 2e9\n[material.failure]\nd0 = 0.05\nc = -1.5\n"
       "[model]\ntype = \"mpm\"\n[mpm]\nupdate_scheme = \"" +
      scheme + "\"\n[time]\nsteps = 1\n";
  const std::string free = D == 2 ? ", \"free\"" : ", \"free\", \"free\"";
  const std::string far = D == 2 ? "1, 1]" : "1, 1, 1]", near = D == 2 ? "-1, -1]" : "-1, -1, -1]";
  const double length = D == 2 ? 0.048 : 0.016;
  s += "[[boundary]]\nname = \"left\"\nkind = \"velocity\"\nregion = { type = \"box\", min = [" + near +
      ", max = [0.0015, " + far.substr(3) + " }\nvalue = [-10" + free + "]\n";
  s += "[[boundary]]\nname = \"right\"\nkind = \"velocity\"\nregion = { type = \"box\", min = [" +
      std::to_string(length - 0.0015) + ", " + near.substr(4) + ", max = [" + far + " }\nvalue = [10" + free + "]\n";
  return s;
}

template <int D>
Fields run_mpm(const io::Scene& scene, const dist::Communicator* comm, double& dt, int steps) {
  auto setup = sim::build_mpm<D>(scene, comm);
  mpm::Simulation<D> sim(setup.settings, setup.particles, scene.file, "mpm", setup.others);
  if (dt <= 0.0) dt = 0.5 * sim.stable_dt();
  Fields out;
  for (int k = 0; k < steps; ++k) {
    sim.step(dt);
    out.broken_across += static_cast<std::int64_t>(sim.newly_failed().size());  // failed points (all processes: summed)
  }
  const auto e = sim.energies();
  out.sums = {e.kinetic,
              e.strain,
              e.dissipated,
              e.external_work,
              e.boundary_work,
              sim.total_mass(),
              sim.pending_boundary_work(dt)};
  for (int a = 0; a < D; ++a) out.sums.push_back(sim.momentum()[a]);
  for (const auto& r : sim.reactions())
    for (int a = 0; a < D; ++a) out.sums.push_back(r[a]);
  const auto& p = setup.particles;
  for (Index i = 0; i < p.n_real; ++i) {
    for (int a = 0; a < D; ++a) out.u.push_back(p.u[i][a]), out.v.push_back(p.v[i][a]);
    const Mat<D> F = sim.state().F.get(i);
    const Mat<3> tau = sim.state().kirchhoff.get(i);
    out.f.insert(out.f.end(), F.data(), F.data() + D * D);
    out.f.insert(out.f.end(), tau.data(), tau.data() + 9);
    out.damage.push_back(sim.eq_plastic_strain(i));
    out.flags.push_back(sim.failed(i));
    out.largest_force = std::max(out.largest_force, tau.cwiseAbs().maxCoeff());
  }
  out.own = p.n_real;
  out.halo = sim.ghost_points();
  return out;
}

template <int D>
bool check_mpm(const std::string& scheme, const dist::Communicator& comm, json& rows) {
  const auto scene = io::parse_scene_text(mpm_scene_text(D, scheme), "ranks_mpm");
  const int steps = D == 2 ? 500 : 120;
  Fields one;
  double dt = 0.0;
  if (comm.rank() == 0) one = run_mpm<D>(scene, nullptr, dt, steps);
  dt = comm.min(comm.rank() == 0 ? dt : std::numeric_limits<double>::infinity());
  const auto many = run_mpm<D>(scene, &comm, dt, steps);
  const auto u = comm.gather(many.u), v = comm.gather(many.v), state = comm.gather(many.f),
             eps = comm.gather(many.damage);
  const auto failed = comm.gather(many.flags);
  const std::int64_t ghosts = comm.sum(many.halo);
  const double ghost_share =
      comm.max(many.own > 0 ? static_cast<double>(many.halo) / static_cast<double>(many.own) : 0.0);
  if (comm.rank() != 0) return true;

  const std::size_t dfailed = failed == one.flags ? 0 : std::max<std::size_t>(1, failed.size());
  const std::size_t du = differing(one.u, u), dv = differing(one.v, v), dstate = differing(one.f, state),
                    deps = differing(one.damage, eps), dsums = differing(one.sums, many.sums);
  const std::string dim = std::to_string(D) + "d", ranks = std::to_string(comm.size());
  // A case that would not test the claim fails: no ghosts, nothing failed, no stress left.
  std::vector<std::string> unfit;
  if (comm.size() > 1 && ghosts == 0) unfit.push_back("no ghost points");
  if (one.broken_across == 0 || !(one.largest_force > 0.0))
    unfit.push_back("no point failed, or no stress is left at the end");
  const test::Gate g = identity_gate(
      "distributed.mpm_" + scheme + "." + dim + "." + ranks + "_ranks",
      "A " + dim + " MPM body (uGIMP, " + scheme + ", J2, " + std::to_string(steps) + " steps, " +
          std::to_string(one.broken_across) +
          " points failed) shall give bitwise identical u, v, F, τ, ε̄_p, failure flags, energies, work, mass, "
          "momentum, reactions and pending boundary work on " +
          ranks + " processes as on one",
      du + dv + dstate + deps + dfailed + dsums,
      "every grid node sums the points that reach it in one process's order (the ghosts bring the other processes' "
      "points), each point's update reads only its nodes, and the grid's and points' sums are taken in one "
      "process's order.",
      unfit);
  const bool ok = test::write_gate(g, "rank_invariance");
  rows.push_back({"mpm (" + scheme + ")", dim, comm.size(), static_cast<double>(one.flags.size()), ghosts, ghost_share,
                  0, steps, one.broken_across, 0, static_cast<double>(du), static_cast<double>(dv),
                  static_cast<double>(dstate), static_cast<double>(dfailed), static_cast<double>(deps),
                  static_cast<double>(dsums)});
  std::cout << (ok ? "PASS " : "FAIL ") << g.id << ": " << g.measured << " values differ, " << one.broken_across
            << " points failed, " << ghosts << " ghost points\n";
  return ok;
}

}  // namespace
}  // namespace pdmpm

int main(int argc, char** argv) {
  using namespace pdmpm;
  dist::MpiSession session(argc, argv);
  const dist::Communicator comm;
  bool ok = true;
  try {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& info : pd::model_table()) {
      // Elastic models; lps_plastic (it needs a hardening law) runs in run_command_invariance.py.
      if (!info.distributed || info.plastic) continue;
      ok = check<2>(info.name, comm, rows) && ok;
      ok = check<3>(info.name, comm, rows) && ok;
    }
    for (const char* scheme : {"musl", "usl"}) {
      ok = check_mpm<2>(scheme, comm, rows) && ok;
      ok = check_mpm<3>(scheme, comm, rows) && ok;
    }
    if (comm.rank() == 0)
      test::record_data(
          "distributed", "rank_invariance_" + std::to_string(comm.size()),
          {{"kind", "table"},
           {"title", std::to_string(comm.size()) + " processes against one, bitwise"},
           {"columns",
            {"model", "dim", "processes", "particles", "halo particles / MPM ghosts of the last step (all processes)",
             "largest halo / own particles", "values sent per exchanged scalar", "steps",
             "bonds broken / points failed", "broken across processes", "u differing", "v differing",
             "f differing (MPM: F, τ)", "bond flags / failure flags differing", "damage (MPM: ε̄_p) differing",
             "sums differing (PD: K, U, W, |W|, pending W, p, L; MPM: K, U, W_p, W, W_b, m, pending W_b, p, R)"}},
           {"rows", rows},
           {"caption",
            "PD: halves pulled apart at ±5 m/s and their 2 mm ends held at that speed, s₀ = 1e-3, Δx = 1 mm, m = "
            "3.015, Δt = 0.7 × Silling–Askari. MPM (uGIMP, cell 2Δx): J2 steel (σ_y = 250 MPa, ductile failure d₀ = "
            "0.05, c = −1.5), 1.5 mm ends pulled at ±10 m/s from t = 0, the 2D plate notched (r = 4 mm), Δt = ½ CFL. "
            "2D plane stress 48 × 24, 3D 16 × 10 × 8; one OpenMP thread per process."}});
  } catch (const std::exception& e) {
    std::cerr << "rank " << comm.rank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  return ok ? 0 : 1;
}
