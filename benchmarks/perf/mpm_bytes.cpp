#include "benchmarks/perf/mpm_bytes.hpp"

#include <cstdint>

#include "solver/mpm/particle_state.hpp"
#include "solver/mpm/simulation.hpp"

namespace pdmpm::perf {

template <int D>
MpmByteAccount mpm_bytes_per_particle_step() {
  constexpr double index = sizeof(Index), real = sizeof(double), vec = sizeof(Vec<D>), matD = sizeof(Mat<D>);
  constexpr double mat3 = sizeof(Mat<3>), stencil = sizeof(mpm::Stencil<D>), history = sizeof(mpm::PointHistory);
  constexpr double cell = sizeof(IVec<D>), polar = sizeof(mpm::PolarLog<D>), flag = sizeof(std::uint8_t);
  // τ as the step moves it: its in-plane entries in 2D (plane stress keeps the others zero).
  constexpr double tau = D == 2 ? 4 * real : mat3;
  MpmByteAccount a;
  // prepare: cells from x0 + u (active list), blocks, stencils in schedule order
  // (x0, u, half-width read, stencil written), external forces zeroed and set, the
  // failure flags of the step cleared, the hardening variable from ε̄_p.
  a.phases.push_back(
      {"prepare", index + 2 * vec + 2 * cell + index + (index + 3 * vec + stencil) + 2 * vec + flag + 2 * real});
  // P2G: mass, velocity, volume, Kirchhoff stress, external force.
  a.phases.push_back({"P2G", index + stencil + real + vec + real + tau + vec});
  // G2P with MUSL's remap: velocity and displacement read and written, mass.
  a.phases.push_back({"G2P", index + stencil + 4 * vec + real});
  // stress: F (read, written), the decomposition (written, read), failure flag twice,
  // history (read, written), hardening variable, τ, J, ε₃₃, energy written,
  // dissipation read and written.
  a.phases.push_back({"stress",
                      (index + stencil + 2 * matD) + (index + flag + matD + polar) +
                          (index + flag + 2 * history + real + polar + tau + 4 * real + 2 * real)});
  for (const auto& p : a.phases) a.total += p.second;
  return a;
}

template MpmByteAccount mpm_bytes_per_particle_step<2>();
template MpmByteAccount mpm_bytes_per_particle_step<3>();

}  // namespace pdmpm::perf
