#pragma once
// [[j_integral]] in a scene: J of a crack tip (domain form, solver/core/j_integral.hpp) in
// history.csv as column j_<name> (J/m²). Each method supplies its samples: elastic PD through
// its stress output (pd/j_samples.hpp), MPM its material points (mpm/j_samples.hpp), the hybrid
// both through MPM's law (hybrid/j_samples.hpp).
#include <string>
#include <vector>

#include "solver/core/j_integral.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::sim {

struct JIntegralOutput {
  std::string name;
  core::JDomain domain;
};

// The scene's J-integrals (2D; none otherwise). Throws InputError(j_integral[k].r_outer) if no
// real particle lies in a ring (of any process's, with `comm`).
template <int D>
std::vector<JIntegralOutput> j_integral_outputs(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real,
                                                const dist::Communicator* comm = nullptr);

inline void add_j_integral_columns(const std::vector<JIntegralOutput>& js, std::vector<std::string>& columns) {
  for (const auto& j : js) columns.push_back("j_" + j.name);
}

// A distributed run's samples: every process's, in the global particle order (each
// process's own in their order, the processes in rank order), on every process, so each
// forms the one-process domain sum. Unchanged with one process (`comm` null).
std::vector<core::JSample> gather_j_samples(std::vector<core::JSample> samples, const dist::Communicator* comm);

// Their values, in the same order; samples(centre, radius) gives the method's samples there.
template <class Samples>
void add_j_integral_values(const std::vector<JIntegralOutput>& js, Samples&& samples, std::vector<double>& row) {
  for (const auto& j : js) row.push_back(core::domain_j_integral(samples(j.domain.tip, j.domain.r_outer), j.domain).J);
}

}  // namespace pdmpm::sim
