#pragma once
// The plane-stress laws of the MPM (J2 with linear hardening, and linear elastic as J2
// that never yields) for eight points at once: the trial stress, the yield check, the
// plane-stress return map of the lanes that yield (the safeguarded Newton iteration
// for the consistency parameter, each lane iterating until its own test stops it),
// the rotation τ = R T Rᵀ, the volume ratio and the stored energy, each by the
// arithmetic of Constitutive<2>::update and j2_return_plane_stress, so the bits are
// theirs. A lane whose trial stress is not finite, or whose Newton step leaves the
// bracket before an upper end is known (the scalar code then searches for one), is
// flagged for the caller to hand to the scalar law.
// verification/unit/mpm/plane_stress_lanes_test.cpp compares the lanes with the law.
#include "solver/mpm/lane_variant.hpp"

namespace pdmpm::mpm {

inline constexpr int kLawLanes = 8;

// The constants of the law (J2Constants' names); linear elastic: yield_stress = ∞.
struct PlaneStressLaw {
  double modulus = 0.0;           // E / (1 − ν²)
  double nu = 0.0;                // ν
  double thickness_strain = 0.0;  // −ν / (1 − ν)
  double yield_stress = 0.0;      // σ_y
  double hardening = 0.0;         // H
  double youngs = 0.0;            // E
  double shear = 0.0;             // G
  double c1 = 0.0;                // E / (3(1 − ν)), the return map's spectral mode 1
};

// Per lane in: ln U = [l00 l01; l01 l11] and R = [c −s; s c] (polar_log<2>), the plastic
// strain (p22 its out-of-plane part) and the equivalent plastic strain the hardening
// uses (alpha = ε̄_p + offset). Out: τ = [k00 k01; k10 k11] (τ₃₃ = 0), J, ε₃₃, energy;
// for the lanes in `yielded` (bit l: lane l) the plastic strain increment (d01 for both
// shear components), Δε̄_p and the dissipation T : Δε_p, which the caller adds to the
// point's history as the scalar law does.
struct PlaneStressLanes {
  double l00[kLawLanes], l01[kLawLanes], l11[kLawLanes], c[kLawLanes], s[kLawLanes];
  double p00[kLawLanes], p11[kLawLanes], p01[kLawLanes], p22[kLawLanes], alpha[kLawLanes];
  double k00[kLawLanes], k01[kLawLanes], k10[kLawLanes], k11[kLawLanes];
  double J[kLawLanes], out_of_plane[kLawLanes], energy[kLawLanes];
  double d00[kLawLanes], d11[kLawLanes], d01[kLawLanes], d22[kLawLanes], d_alpha[kLawLanes];
  double dissipation[kLawLanes];
  unsigned yielded = 0;
};

// Lane l's plastic strain: ε_p, or for linear elasticity (which has none, whatever a
// history holds) zeros that subtract and add nothing — +0 and, for the ε₃₃ sum, −0.
template <class Mat3>
void set_plastic_lane(PlaneStressLanes& lanes, int l, const Mat3& plastic_strain, bool linear_elastic) {
  lanes.p00[l] = linear_elastic ? 0.0 : plastic_strain(0, 0);
  lanes.p11[l] = linear_elastic ? 0.0 : plastic_strain(1, 1);
  lanes.p01[l] = linear_elastic ? 0.0 : plastic_strain(0, 1);
  lanes.p22[l] = linear_elastic ? -0.0 : plastic_strain(2, 2);
}

// Returns a bit per lane (bit l: lane l) the lanes leave to the scalar law.
unsigned plane_stress_lanes(const PlaneStressLaw& law, PlaneStressLanes& lanes);

using PlaneStressLanesFunction = unsigned (*)(const PlaneStressLaw&, PlaneStressLanes&);
std::vector<LaneVariant<PlaneStressLanesFunction>> plane_stress_lanes_variants();

}  // namespace pdmpm::mpm
