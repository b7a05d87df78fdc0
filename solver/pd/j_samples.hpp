#pragma once
// The particles of an elastic PD body as samples of the J-integral's domain form
// (solver/core/j_integral.hpp): the displacement gradient of the stress output (F − I from
// the intact bonds, solver/pd/stress.hpp), Hooke's stress of its symmetric part and the
// energy ½ σ : ε. Elastic models only: a plastic body's stress is not Hooke's law of its
// total strain.
#include <vector>

#include "solver/core/j_integral.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::pd {

// Samples of the real particles within `radius` of `centre` (reference positions).
std::vector<core::JSample> elastic_j_samples(const System<2>& sys, const Vec<2>& centre, double radius);

}  // namespace pdmpm::pd
