#include "solver/dist/distribute.hpp"

#include <memory>

#include "solver/dist/halo_exchange.hpp"

namespace pdmpm::dist {

template <int D>
core::Particles<D> distribute(const Communicator& comm, const core::BodySites<D>& body, double family_ratio,
                              Ownership& ownership) {
  ownership.global_count = body.size();
  ownership.own = owned_range(body.size(), comm.rank(), comm.size());
  auto halo = halo_of(body, core::Stencil<D>::build(family_ratio), ownership.own);
  ownership.halo = std::move(halo.global);
  ownership.whole_body_bonds = halo.own_bonds;
  // Own particles as the real ones, then the halo as remote ghosts, both in global order.
  auto local = body.particles(ownership.own.begin, ownership.own.end, ownership.halo);
  auto exchange = std::make_shared<HaloExchange>(comm, body.size(), ownership.own, local.n_real, ownership.halo);
  ownership.values_sent = exchange->values_sent();
  ownership.neighbours = exchange->neighbours();
  ownership.exchange = exchange;
  local.remote = std::move(exchange);
  return local;
}

template core::Particles<1> distribute<1>(const Communicator&, const core::BodySites<1>&, double, Ownership&);
template core::Particles<2> distribute<2>(const Communicator&, const core::BodySites<2>&, double, Ownership&);
template core::Particles<3> distribute<3>(const Communicator&, const core::BodySites<3>&, double, Ownership&);

}  // namespace pdmpm::dist
