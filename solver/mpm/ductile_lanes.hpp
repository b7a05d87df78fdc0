#pragma once
// The ductile fracture strain ε_f = d₀ exp(c η) of eight plane-stress points at once
// (Noorian et al. eqs 8–9; stress_measures.hpp), η the triaxiality of σ = τ / J. Each
// lane does triaxiality's and fracture_strain's arithmetic — the divisions and the
// square root in vector instructions, the exponential by the same library call per
// lane — so the bits are the scalar functions'. Plane stress: τ₃₃ and the out-of-plane
// shears are zero. verification/unit/mpm/ductile_lanes_test.cpp compares the lanes
// with the scalar functions.
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"

namespace pdmpm::mpm {

// Per lane: ε_f of the stress τ = [k00 k01; k10 k11] and volume ratio J the
// plane-stress law's lanes put out (plane_stress_lanes.hpp).
void fracture_strain_lanes(double d0, double c, const PlaneStressLanes& law_out, double* fracture_strain);

using FractureStrainLanesFunction = void (*)(double, double, const PlaneStressLanes&, double*);
std::vector<LaneVariant<FractureStrainLanesFunction>> fracture_strain_lanes_variants();

}  // namespace pdmpm::mpm
