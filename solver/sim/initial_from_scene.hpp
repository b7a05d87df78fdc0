#pragma once
// Turns a scene's [[initial]] tables into bc::InitialCondition (particles
// selected, expressions parsed), for the PD, MPM and hybrid setups.
#include <vector>

#include "solver/bc/initial_condition.hpp"
#include "solver/core/particles.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::sim {

// In file order. A table's region (none: the whole body) selects real particles
// by reference position; InputError naming the table's region when it selects none
// (with `comm`, none on any process of a distributed run).
template <int D>
std::vector<bc::InitialCondition<D>> make_initial_conditions(const io::Scene& scene, const core::Particles<D>& p,
                                                             const dist::Communicator* comm = nullptr);

}  // namespace pdmpm::sim
