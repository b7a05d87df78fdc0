#pragma once
// Scene choices of the stabilized hybrid PD model (solver/pd/hpd.hpp): the constitutive
// law its bonds evaluate, and how many sub-horizon points a bond needs for an nD strain.
#include <array>

#include "solver/core/named_enum.hpp"

namespace pdmpm::pd {

// axial_1d: the 1D law on the bond's own stretch, no shear (bond-based PD, PMB's constant);
// linear_elastic: Hooke's law of the setting on the bond-midpoint strain (nD);
// j2: MPM's J2 law with linear hardening (solver/mpm/j2_plasticity.hpp) on the bond-midpoint
// deformation, a plastic state per bond side.
enum class HpdLaw { axial_1d, linear_elastic, j2 };

constexpr std::array<EnumName<HpdLaw>, 3> names(HpdLaw) {
  return {{{HpdLaw::axial_1d, "axial_1d"}, {HpdLaw::linear_elastic, "linear_elastic"}, {HpdLaw::j2, "j2"}}};
}

struct HpdOptions {
  HpdLaw law = HpdLaw::linear_elastic;
  // Fewest points (the bond's two ends included) a sub-horizon needs for the least-squares
  // midpoint strain; fewer, or points on one line, and the bond falls back to its axial
  // strain. 0: D + 1, the fewest that determine an affine field.
  int min_overlap = 0;
  // Weight of the bond's two ends in the least-squares fit, relative to the other points
  // (each weighted by its volume). Large: the fitted gradient maps the bond itself (nearly)
  // exactly, as the 1D law's stretch does, and the sub-horizon supplies the other components;
  // this is what resists the checkerboard mode (1: plain fit, 17× weaker there; docs/models/hpd.md).
  // 10³ is within 10⁻³ of the exactly constrained fit and keeps the fit's matrix well conditioned.
  double end_weight = 1000.0;
  // Stiffness g of the sub-horizon fit's residual, in units of the shear modulus: each bond side
  // adds the energy ½ G Σ_l w_l |r_l|², r_l = u_l − ū − H (x_l − x̄) the part of its sub-horizon's
  // displacement the affine fit does not explain, G = 2gμ/δ² · V_i a_ij / Σ_l V_l. Zero for
  // affine fields (patch tests, the stress and the energy of a homogeneous deformation
  // unchanged), the virial of its forces is zero, rigid motions cost nothing; it resists the
  // short-wave modes the bond-midpoint fit alone resists weakly in 3D (docs/models/hpd.md).
  // 1: the residual, read as a strain |r|/δ, costs what a shear strain of that size costs
  // (energy density μ ε², weighted mean over the sub-horizon); 0: off.
  double stabilization = 1.0;
  int min_points(int dim) const { return min_overlap > 0 ? min_overlap : dim + 1; }
};

}  // namespace pdmpm::pd
