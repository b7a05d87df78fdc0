#include "solver/time/dynamic_relaxation.hpp"
#include "solver/sim/pd_setup.hpp"

#include <gtest/gtest.h>

#include "solver/io/scene.hpp"

namespace pdmpm::time {
namespace {

// A bar (1D PMB, no partial volumes) fixed at the left end with an end traction
// σ on the right layer relaxes to u(x) = σ x / E_eff in its interior, where E_eff
// is the discrete lattice modulus (the continuum E up to the lattice sum).
TEST(DynamicRelaxation, BarUnderEndLoadReachesUniformStrain) {
  const auto scene = io::parse_scene_text(R"(
[scene]
id = "bar"
[discretization]
dimension = 1
spacing = 1e-3
horizon_ratio = 3.015
area = 1e-6
partial_volume = "none"
[[shape]]
type = "segment"
min = [0]
max = [0.1]
[material]
density = 7850
youngs_modulus = 200e9
[model]
type = "pmb"
[time]
integrator = "adr"
tolerance = 1e-9
max_steps = 200000
[[boundary]]
kind = "fixed"
region = { type = "box", min = [0], max = [0.0035] }
[[boundary]]
kind = "traction"
value = [1e6]
layer = 1e-3
region = { type = "box", min = [0.0995], max = [0.1] }
)", "bar.toml");
  auto setup = sim::build_pd<1>(scene);
  auto st = sim::make_simulation(setup);
  time::DynamicRelaxation<1> relax(st);
  const auto r = relax.solve(1.0, 1e-9, 200000);
  ASSERT_TRUE(r.converged) << "residual " << r.residual << " after " << r.iterations;
  // Strain from two interior particles far from both ends.
  const auto& p = setup.system.particles;
  auto u_at = [&](double x) {
    for (Index i = 0; i < p.n_real; ++i)
      if (std::abs(p.x0[i][0] - x) < 1e-9) return p.u[i][0];
    return std::nan("");
  };
  const double strain = (u_at(0.0705) - u_at(0.0305)) / 0.04;
  // Lattice modulus of the PMB bar without partial volumes: Σ_j c |ξ| V_j / A
  // over the stencil, divided by the continuum ∫ c |ξ| dξ = E.
  double discrete = 0.0, continuum = 0.0;
  const double delta = 3.015e-3;
  for (int k = 1; k <= 3; ++k) discrete += 2 * (k * 1e-3) * 1e-3;
  continuum = delta * delta;
  const double E_eff = 200e9 * discrete / continuum;
  EXPECT_NEAR(strain / (1e6 / E_eff), 1.0, 1e-6);
}

}  // namespace
}  // namespace pdmpm::time
