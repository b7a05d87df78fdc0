#include "solver/pd/partial_volume.hpp"

namespace pdmpm::pd {

double partial_volume(PartialVolume pv, double r, double delta, double dx) {
  const double reach = pv == PartialVolume::extended ? delta + 0.5 * dx : delta;
  // Same relative slack as the stencil, so a bond the stencil admits gets its β.
  if (r > reach * (1.0 + 1e-10)) return 0.0;
  if (pv == PartialVolume::none || r <= delta - 0.5 * dx) return 1.0;
  const double beta = (delta + 0.5 * dx - r) / dx;
  return beta > 0.0 ? beta : 0.0;
}

double family_ratio(PartialVolume pv, double delta, double dx) {
  return (pv == PartialVolume::extended ? delta + 0.5 * dx : delta) / dx;
}

}  // namespace pdmpm::pd
