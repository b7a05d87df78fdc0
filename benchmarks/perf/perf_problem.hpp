#pragma once
// The problem every part of the performance driver runs: LAMMPS' PERI example
// target as in verification/scenes/disk_impact_elastic.toml (cylinder R = H = 5 mm,
// bottom face held, rigid sphere, LAMMPS' contact and indenter rules, no bond
// breaking), on a lattice `refine` times finer with δ = 3.0002 Δx kept, so
// refine = 3 gives 87 k particles and 9.9·10⁶ bond sides — the size issue 6 names.
//  - PMB: peri/pmb (constant ω); LPS: peri/lps (ω = 1/|ξ|, ν = 1/4: the same E, K);
//  - the sphere starts 0.1 mm inside the top face, so a run of a few steps moves
//    the body (from the scene's start, 0.05 mm above, it would not touch it);
//  - Δt = 1e-7 s / refine: LAMMPS' example step scaled with Δx, the same fraction
//    of the stable step at every refinement.
#include <string>

#include "solver/io/scene.hpp"

namespace pdmpm::perf {

// model: "pmb" or "lps"; refine: an integer ≥ 1 (the held bottom face stays on a lattice plane).
io::Scene perf_scene(const std::string& model, int refine);
double perf_dt(int refine);

}  // namespace pdmpm::perf
