#pragma once
// Rigid spherical (3D) / cylindrical (2D) indenter moving at constant velocity,
// pushing particles with F = k (R − r)² along the outward normal for r < R
// (docs/verification/disk_impact_lammps.md; the form of LAMMPS' fix indent). F is a force per particle
// in N, or with `force_density` a force density in N/m³: LAMMPS' PERI atoms
// carry force densities (their "mass" is the density), so fix indent's k acts
// per unit volume there.
#include "solver/core/particles.hpp"

namespace pdmpm::bc {

template <int D>
struct Indenter {
  Vec<D> center0 = Vec<D>::Zero();
  Vec<D> velocity = Vec<D>::Zero();
  double radius = 0.0;
  double stiffness = 0.0;
  bool force_density = false;

  Vec<D> center(double t) const { return center0 + t * velocity; }
  // Adds F/V_i to p.b of every particle inside the indenter at time t and
  // returns the total force the particles exert on the indenter.
  Vec<D> add_forces(core::Particles<D>& p, double t) const;
};

}  // namespace pdmpm::bc
