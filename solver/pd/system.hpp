#pragma once
// Everything a peridynamic force model acts on: particles, families, the bond
// table and the per-bond broken flags.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/core/families.hpp"
#include "solver/core/particles.hpp"
#include "solver/pd/bond_table.hpp"
#include "solver/pd/material.hpp"

namespace pdmpm::pd {

static_assert(core::kBondPadding >= kernels::lanes, "bond arrays must be padded for whole-block kernel loads");

template <int D>
struct System {
  core::Particles<D> particles;
  core::Families<D> families;
  BondTable<D> table;
  std::vector<std::uint8_t> broken;  // per bond; 1 = μ = 0 for ever after

  Setting setting = Setting::solid3d;
  Elastic material;
  double delta = 0.0;    // horizon δ
  double measure = 1.0;  // thickness (2D), area (1D), 1 (3D)
  Influence influence = Influence::constant;
  PartialVolume partial_volume = PartialVolume::seed001;
  // LPS weighted volume: false → the discrete sum over each family (SPEC §3; exact
  // patch tests), true → the continuum integral for every particle (seed 004 eq 15).
  bool continuum_weighted_volume = false;

  double spacing() const { return particles.lattice.spacing; }
  Index n_real() const { return particles.n_real; }

  kernels::FamilyView family_view() {
    return {families.n_owners(), particles.size(), families.offsets.data(), families.neighbor.data(),
            families.shape.data(), broken.data()};
  }

  // Whether every particle (ghosts too) has the same volume, as on a lattice body.
  bool uniform_volume() const {
    const auto& v = particles.volume;
    return std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
  }

  // Build families and the bond table for the current particles.
  void connect() {
    families = core::Families<D>::build(particles, family_ratio(partial_volume, delta, spacing()));
    table = BondTable<D>::build(families.stencil, spacing(), delta, influence, partial_volume);
    broken.assign(families.n_bonds() + core::kBondPadding, 0);
  }
};

}  // namespace pdmpm::pd
