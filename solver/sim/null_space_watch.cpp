#include "solver/sim/null_space_watch.hpp"

#include <fmt/format.h>

namespace pdmpm::sim {

std::optional<std::string> NullSpaceWatch::check(double kinetic, double grid_kinetic, double strain, std::int64_t step,
                                                 double t, const GridSampling& grid) {
  const bool moving = kinetic > kNullSpaceKineticFloor * (kinetic + strain);
  const double share = moving ? (kinetic - grid_kinetic) / kinetic : 0.0;
  if (!(share > kNullSpaceShareLimit)) {
    above_since_ = -1;
    return std::nullopt;
  }
  if (above_since_ < 0) above_since_ = step, above_since_t_ = t;
  if (step - above_since_ < kNullSpaceSustainSteps) return std::nullopt;
  return fmt::format(
      "from step {} (t = {:.4g} s) to step {} (t = {:.4g} s) more than {:.0f} % of the MPM particles' kinetic energy "
      "({:.0f} % now) moves them against each other within the grid's cells, which the grid cannot see (the null space "
      "of its "
      "particle-to-grid map): either such a mode is growing, which wrecks the run (FLIP keeps these modes; this grid "
      "has {:.3g} particles per cell along an axis and flip = {:.3g}: 2 or more, mpm.cell_factor ≥ 2, or a PIC share, "
      "mpm.flip < 1, damp them), or the body is coming apart at the scale of a cell (docs/models/mpm.md, "
      "\"Null-space modes\")",
      above_since_, above_since_t_, step, t, 100.0 * kNullSpaceShareLimit, 100.0 * share, grid.particles_per_cell,
      grid.flip);
}

}  // namespace pdmpm::sim
