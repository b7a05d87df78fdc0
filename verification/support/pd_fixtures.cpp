#include "verification/support/pd_fixtures.hpp"

#include <algorithm>
#include <limits>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::test {

template <int D>
pd::System<D> make_block(const BlockSpec& spec) {
  core::Lattice<D> lat;
  lat.spacing = spec.spacing;
  core::Geometry<D> g;
  g.add(std::make_unique<core::Box<D>>(Vec<D>::Zero(), Vec<D>::Constant((spec.sites - 1) * spec.spacing)));
  double vol = std::pow(spec.spacing, D) * (D == 3 ? 1.0 : spec.measure);
  pd::System<D> sys;
  sys.particles = core::fill_lattice<D>(g, lat, vol);
  sys.setting = spec.setting;
  sys.material = spec.material;
  sys.delta = spec.horizon_ratio * spec.spacing;
  sys.measure = D == 3 ? 1.0 : spec.measure;
  sys.influence = spec.influence;
  sys.partial_volume = spec.partial_volume;
  sys.connect();
  return sys;
}

template <int D>
double distance_to_boundary(const pd::System<D>& sys, Index i) {
  double hi = 0.0;
  for (const auto& x : sys.particles.x0) hi = std::max(hi, x.maxCoeff());
  double d = std::numeric_limits<double>::max();
  for (int a = 0; a < D; ++a) d = std::min({d, sys.particles.x0[i][a], hi - sys.particles.x0[i][a]});
  return d;
}

template pd::System<1> make_block<1>(const BlockSpec&);
template pd::System<2> make_block<2>(const BlockSpec&);
template pd::System<3> make_block<3>(const BlockSpec&);
template double distance_to_boundary<1>(const pd::System<1>&, Index);
template double distance_to_boundary<2>(const pd::System<2>&, Index);
template double distance_to_boundary<3>(const pd::System<3>&, Index);

}  // namespace pdmpm::test
