#pragma once
// The ductile fracture strain ε_f = d₀ exp(c η) of eight plane-stress points at once
// (Noorian et al. eqs 8–9; stress_measures.hpp), η the triaxiality of σ = τ / J. Each
// lane does triaxiality's and fracture_strain's arithmetic — the divisions and the
// square root in vector instructions, the exponential by the same library call per
// lane — so the bits are the scalar functions'. Plane stress: τ₃₃ and the out-of-plane
// shears are zero. verification/unit/mpm/ductile_lanes_test.cpp compares the lanes
// with the scalar functions.
#include "solver/core/material.hpp"
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"

namespace pdmpm::mpm {

// Per lane in `needed` (bit l: lane l): ε_f of the stress τ = [k00 k01; k10 k11] and
// volume ratio J the plane-stress law's lanes put out (plane_stress_lanes.hpp). The
// other lanes get d₀ (ε_f at η = 0) without the exponential: the caller leaves out the
// points whose criterion cannot depend on ε_f (ductile_criterion_needs_fracture_strain).
void fracture_strain_lanes(double d0, double c, const PlaneStressLanes& law_out, unsigned needed,
                           double* fracture_strain);

// The lanes (of the first n) whose ductile criterion can depend on ε_f, for the law's
// lanes `law` (its alpha: ε̄_p + offset before the update; its yielded mask): a point that
// did not flow this step adds 0 / ε_f = 0 to its damage (rule "accumulated"), and one with
// no plastic strain (ε̄_p + offset ≤ 0, rule "strain") cannot reach an ε_f > 0. In plane
// stress ε_f > 0 always: σ_eq ≥ 1.5 |σ_m| bounds |η| by 2/3, so ε_f ≥ d₀ e^{−2|c|/3}, which
// only a |c| beyond ~1000 rounds to zero (then every lane is needed).
unsigned lanes_needing_fracture_strain(const core::DuctileFailure& rule, const PlaneStressLanes& law, int n);

using FractureStrainLanesFunction = void (*)(double, double, const PlaneStressLanes&, unsigned, double*);
std::vector<LaneVariant<FractureStrainLanesFunction>> fracture_strain_lanes_variants();

}  // namespace pdmpm::mpm
