#pragma once
// Kinetic energy the MPM grid cannot see. The particle-to-grid map has a null space:
// oscillating particle velocities whose nodal momenta cancel (Gritton & Berzins 2017). FLIP
// carries such velocities from step to step and nothing restrains them; with one particle
// per cell along an axis a mode of this kind grows until it wrecks the run (Brackbill's
// ringing instability; measured in docs/models/mpm.md, "Null-space modes"). Its share of the
// particles' kinetic energy E_k is
//   (E_k − E_k,grid) / E_k,   E_k,grid = Σ_I ½|p_I|²/m_I ≤ E_k (Cauchy–Schwarz),
// with p_I the nodal momenta MUSL remaps from the current particle velocities.
#include <cstdint>
#include <optional>
#include <string>

namespace pdmpm::sim {

// Warn when the share stays above this limit ... (stable plates of docs/models/mpm.md: at
// most 0.21 once their start-up has passed; the unstable one crosses it about 5 µs before its
// kinetic energy grows forty-fold, and stays above)
inline constexpr double kNullSpaceShareLimit = 0.25;
// ... for this many steps: a grip that starts at full speed puts a quarter of the first
// steps' kinetic energy in the null space for a few steps (measured: 10 steps).
inline constexpr std::int64_t kNullSpaceSustainSteps = 100;
// Only while the kinetic energy is at least this fraction of kinetic + strain energy: a
// body nearly at rest has a kinetic energy of round-off, and any share of it.
inline constexpr double kNullSpaceKineticFloor = 1e-3;

struct GridSampling {
  double particles_per_cell = 2.0;  // grid cell / lattice spacing
  double flip = 1.0;                // FLIP fraction of the velocity update
};

class NullSpaceWatch {
 public:
  // The warning for the user once the share has stayed above the limit for
  // kNullSpaceSustainSteps steps (nullopt otherwise); called at increasing steps.
  std::optional<std::string> check(double kinetic, double grid_kinetic, double strain, std::int64_t step, double t,
                                   const GridSampling& grid);

 private:
  std::int64_t above_since_ = -1;  // the first step of the current run of checks above the limit
  double above_since_t_ = 0.0;     // its time
};

}  // namespace pdmpm::sim
