#pragma once
// One body, several methods: a scene integrated as written and again by MPM J2, and the
// gauge reading both are compared by (the same-body gates of lps_plastic and hpd).
#include <vector>

#include "solver/io/scene.hpp"
#include "verification/support/scene_gate.hpp"

namespace pdmpm::test {

// The scene with MPM J2 in place of the PD model (GIMP, MUSL, cell 2Δx: the defaults, Noorian
// et al.'s choices); everything else (body, material, grips, probes, output) as written.
io::Scene as_mpm_j2(io::Scene s);

// Mean axial strain (least-squares slope of u_x against x₀) and mean σ_xx of the particles of
// one frame whose reference positions lie in the box.
struct GaugeReading {
  double strain = 0.0, stress = 0.0;
};
std::vector<GaugeReading> gauge_history(const GateRun& run, double x_lo, double x_hi, double y_lo, double y_hi);

// y at xq on the polyline (x, y), x ascending; the end values beyond its ends.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq);

}  // namespace pdmpm::test
