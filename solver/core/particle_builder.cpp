#include "solver/core/particle_builder.hpp"

#include "solver/core/body_sites.hpp"

namespace pdmpm::core {

template <int D>
Particles<D> fill_lattice(const Geometry<D>& geometry, const Lattice<D>& lattice, double volume) {
  const auto body = body_sites<D>(geometry, lattice, volume);
  return body.particles(0, body.size());
}

template Particles<1> fill_lattice(const Geometry<1>&, const Lattice<1>&, double);
template Particles<2> fill_lattice(const Geometry<2>&, const Lattice<2>&, double);
template Particles<3> fill_lattice(const Geometry<3>&, const Lattice<3>&, double);

}  // namespace pdmpm::core
