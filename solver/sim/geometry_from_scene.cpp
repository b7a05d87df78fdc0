#include "solver/sim/geometry_from_scene.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "solver/core/error.hpp"

namespace pdmpm::sim {

template <int D>
core::BodySites<D> body_sites_of(const io::Scene& s) {
  const auto geometry = make_geometry<D>(s.shapes);
  // Particles are indexed by 32-bit integers (families store them per bond): a
  // lattice that could hold more is refused before it is filled site by site.
  double sites = 1.0;
  const auto box = geometry.bounds();
  for (int a = 0; a < D; ++a) sites *= std::ceil((box.max[a] - box.min[a]) / s.spacing) + 1.0;
  if (!(sites <= static_cast<double>(std::numeric_limits<Index>::max())))
    throw InputError(s.file, "discretization.spacing",
                     fmt::format("{} m puts up to {:.3g} lattice sites in the shapes' bounding box; pdmpm indexes "
                                 "particles with 32-bit integers (at most {}): use a larger spacing",
                                 s.spacing, sites, std::numeric_limits<Index>::max()));
  const double volume = std::pow(s.spacing, D) * (D == 3 ? 1.0 : s.measure);
  auto body = core::body_sites<D>(geometry, make_lattice<D>(s, geometry), volume);
  if (body.size() == 0)
    throw InputError(s.file, "shape",
                     "the shapes contain no lattice site: check their extents against discretization.spacing");
  return body;
}

template <int D>
core::Particles<D> fill_body(const io::Scene& s) {
  const auto body = body_sites_of<D>(s);
  return body.particles(0, body.size());
}

template <int D>
core::Lattice<D> make_lattice(const io::Scene& s, const core::Geometry<D>& g) {
  core::Lattice<D> lat;
  lat.spacing = s.spacing;
  lat.origin =
      s.lattice_origin ? to_vec<D>(*s.lattice_origin) : Vec<D>(g.bounds().min + Vec<D>::Constant(0.5 * s.spacing));
  return lat;
}

template <int D>
core::Geometry<D> make_geometry(const std::vector<io::ShapeSpec>& shapes) {
  core::Geometry<D> g;
  for (const auto& s : shapes) {
    std::unique_ptr<core::Shape<D>> shape;
    if (s.type == "box") {
      shape = std::make_unique<core::Box<D>>(to_vec<D>(s.min), to_vec<D>(s.max));
    } else if (s.type == "ball") {
      shape = std::make_unique<core::Ball<D>>(to_vec<D>(s.center), s.radius);
    } else if constexpr (D == 3) {
      shape = std::make_unique<core::Cylinder>(to_vec<3>(s.center), s.axis, s.radius, s.height);
    }
    if (s.subtract)
      g.subtract(std::move(shape));
    else
      g.add(std::move(shape));
  }
  return g;
}

template <int D>
std::vector<Index> select_particles(const std::vector<Vec<D>>& x0, Index n_real, const core::Geometry<D>& region,
                                    double spacing) {
  std::vector<Index> out;
  const double tol = 1e-9 * spacing;  // the same closed-boundary rule as the lattice fill
  for (Index i = 0; i < n_real; ++i)
    if (region.contains(x0[i], tol)) out.push_back(i);
  return out;
}

template core::Geometry<1> make_geometry<1>(const std::vector<io::ShapeSpec>&);
template core::Geometry<2> make_geometry<2>(const std::vector<io::ShapeSpec>&);
template core::Geometry<3> make_geometry<3>(const std::vector<io::ShapeSpec>&);
template std::vector<Index> select_particles<1>(const std::vector<Vec<1>>&, Index, const core::Geometry<1>&, double);
template std::vector<Index> select_particles<2>(const std::vector<Vec<2>>&, Index, const core::Geometry<2>&, double);
template core::BodySites<1> body_sites_of<1>(const io::Scene&);
template core::BodySites<2> body_sites_of<2>(const io::Scene&);
template core::BodySites<3> body_sites_of<3>(const io::Scene&);
template core::Particles<1> fill_body<1>(const io::Scene&);
template core::Particles<2> fill_body<2>(const io::Scene&);
template core::Particles<3> fill_body<3>(const io::Scene&);
template core::Lattice<1> make_lattice<1>(const io::Scene&, const core::Geometry<1>&);
template core::Lattice<2> make_lattice<2>(const io::Scene&, const core::Geometry<2>&);
template core::Lattice<3> make_lattice<3>(const io::Scene&, const core::Geometry<3>&);
template std::vector<Index> select_particles<3>(const std::vector<Vec<3>>&, Index, const core::Geometry<3>&, double);

}  // namespace pdmpm::sim
