#include "solver/sim/mpm_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "solver/bc/expression.hpp"
#include "solver/core/error.hpp"
#include "solver/core/particle_builder.hpp"
#include "solver/dist/decomposition.hpp"
#include "solver/dist/particle_share.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/sim/geometry_from_scene.hpp"
#include "solver/sim/initial_from_scene.hpp"

namespace pdmpm::sim {
namespace {

template <int D>
bc::ExpressionVariables variables(const Vec<D>& x, double t) {
  bc::ExpressionVariables v;
  v.t = t;
  v.x = x[0];
  if constexpr (D > 1) v.y = x[1];
  if constexpr (D > 2) v.z = x[2];
  return v;
}

// Per component: the expression, or nothing for "free".
template <int D>
std::vector<std::shared_ptr<bc::Expression>> parse_components(const io::BoundarySpec& b) {
  std::vector<std::shared_ptr<bc::Expression>> e(D);
  for (int a = 0; a < D; ++a)
    if (b.value[a] != "free") e[a] = std::make_shared<bc::Expression>(bc::Expression::parse(b.value[a]));
  return e;
}

template <int D>
void add_boundary(const io::Scene& s, std::size_t index, MpmGridSettings<D>& out) {
  const io::BoundarySpec& b = s.boundaries[index];
  if (b.kind == io::BoundaryKind::traction) {
    const auto value = parse_components<D>(b);
    for (int a = 0; a < D; ++a)
      if (!value[a]) throw InputError(s.file, b.key + ".value", "a traction component cannot be \"free\" (use 0)");
    // The scene's traction acts on a layer of thickness `layer` (force density t/layer);
    // mpm::Traction spreads t over a layer of one spacing, so scale by Δx/layer.
    const double scale = b.layer > 0.0 ? s.spacing / b.layer : 1.0;
    for (const auto& r : b.region) {
      mpm::Traction<D> t;
      t.name = b.name;
      t.min = to_vec<D>(r.min);
      t.max = to_vec<D>(r.max);
      t.traction_field = [value, scale](const Vec<D>& X, double time) {
        Vec<D> traction;
        for (int a = 0; a < D; ++a) traction[a] = scale * (*value[a])(variables<D>(X, time));
        return traction;
      };
      out.settings.tractions.push_back(std::move(t));
    }
    return;
  }
  for (const auto& r : b.region) {
    mpm::GridBc<D> g;
    g.name = b.name;
    g.min = to_vec<D>(r.min);
    g.max = to_vec<D>(r.max);
    if (b.kind == io::BoundaryKind::fixed) {
      g.kind = mpm::BcKind::fixed;
    } else {
      g.kind = mpm::BcKind::velocity;
      g.moving = b.moving;
      const auto value = parse_components<D>(b);
      for (int a = 0; a < D; ++a) g.components[a] = value[a] != nullptr;
      g.field_depends_on_position =
          std::any_of(value.begin(), value.end(), [](const auto& e) { return e && e->depends_on_position(); });
      g.velocity_field = [value](const Vec<D>& x, double time) {
        Vec<D> v = Vec<D>::Zero();
        for (int a = 0; a < D; ++a)
          if (value[a]) v[a] = (*value[a])(variables<D>(x, time));
        return v;
      };
    }
    out.settings.boundaries.push_back(std::move(g));
    out.grid_bc_source.push_back(static_cast<int>(index));
  }
}

}  // namespace

template <int D>
MpmGridSettings<D> translate_mpm(const io::Scene& s) {
  const io::MpmSpec& m = *s.mpm;
  const auto geometry = make_geometry<D>(s.shapes);
  MpmGridSettings<D> out;
  auto& st = out.settings;
  st.setting = s.setting;
  st.material = {m.constitutive, s.material, s.hardening};
  st.shape = m.shape;
  st.gimp_domain = m.gimp_domain;
  st.scheme = m.scheme;
  st.flip = m.flip;
  st.cell_size = m.cell_size;
  st.cell_factor = m.cell_factor;
  st.padding_cells = m.padding_cells;
  if (!m.domain_min.empty()) {
    Vec<D> lo, hi;
    for (int a = 0; a < D; ++a) {
      lo[a] = m.domain_min[static_cast<std::size_t>(a)];
      hi[a] = m.domain_max[static_cast<std::size_t>(a)];
    }
    st.domain_min = lo;
    st.domain_max = hi;
  }
  st.damping_viscous = m.damping_viscous;
  st.damping_local = m.damping_local;
  st.nonlocal = m.nonlocal;
  st.failure = s.failure;
  st.dt = s.time.dt.value_or(0.0);
  st.cfl = s.time.safety_factor;

  // Grid lines through the body's lower faces (particles sit symmetrically in the
  // cells), and through every symmetry plane.
  const auto bounds = geometry.bounds();
  st.origin = bounds.min;
  for (const auto& sym : s.symmetries) {
    mpm::GridBc<D> g;
    g.name = "symmetry_" + std::string(1, "xyz"[sym.axis]);
    g.kind = mpm::BcKind::symmetry;
    g.axis = sym.axis;
    g.position = sym.position;
    const double tol = 1e-9 * s.spacing;
    if (bounds.min[sym.axis] >= sym.position - tol)
      g.side = +1;
    else if (bounds.max[sym.axis] <= sym.position + tol)
      g.side = -1;
    else
      throw InputError(s.file, sym.key + ".position",
                       "the symmetry plane cuts the body: it must lie on a face of the body");
    const double gap = g.side > 0 ? bounds.min[sym.axis] - sym.position : sym.position - bounds.max[sym.axis];
    if (!(gap <= s.spacing))  // a plane off the body mirrors nothing
      throw InputError(s.file, sym.key + ".position",
                       fmt::format("the symmetry plane is {} m from the body: it must lie on a face of the body "
                                   "(at {} or {} m on this axis)",
                                   gap, bounds.min[sym.axis], bounds.max[sym.axis]));
    st.origin[sym.axis] = sym.position;
    st.boundaries.push_back(std::move(g));
    out.grid_bc_source.push_back(-1);
  }
  for (std::size_t k = 0; k < s.boundaries.size(); ++k) add_boundary<D>(s, k, out);

  if (!s.body_force.empty()) {
    std::vector<bc::Expression> b;
    for (int a = 0; a < D; ++a) b.push_back(bc::Expression::parse(s.body_force[a]));
    const double rho = s.material.rho;
    st.body_acceleration = [b, rho](const Vec<D>& X, double t) {
      Vec<D> acc;
      for (int a = 0; a < D; ++a) acc[a] = b[a](variables<D>(X, t)) / rho;
      return acc;
    };
  }
  return out;
}

template <int D>
MpmSetup<D> build_mpm(const io::Scene& s, const dist::Communicator* comm) {
  MpmSetup<D> out;
  if (comm && comm->size() > 1) {
    // Material points never change owner: each process makes and keeps a contiguous range
    // of the global (Morton) order; its ghosts are found afresh every step
    // (mpm/other_processes.hpp). Probes and J-integral rings are placed in the whole body.
    const auto body = body_sites_of<D>(s);
    out.global_count = body.size();
    const dist::OwnedRange own = dist::owned_range(body.size(), comm->rank(), comm->size());
    out.particles = body.particles(own.begin, own.end);
    out.others = std::make_shared<dist::ParticleShare>(*comm, own);
    out.probes = locate_probes<D>(s, out.particles.x0, out.particles.n_real, comm, own, body.size());
    out.j_integrals = j_integral_outputs<D>(s, out.particles.x0, out.particles.n_real, comm);
  } else {
    out.particles = fill_body<D>(s);
    out.global_count = out.particles.n_real;
    out.probes = locate_probes<D>(s, out.particles.x0, out.particles.n_real);
    out.j_integrals = j_integral_outputs<D>(s, out.particles.x0, out.particles.n_real);
  }
  for (auto& k : out.particles.kind) k = core::ParticleKind::mpm;
  // Before the simulation exists: its grid covers the displaced body and its first
  // stable step sees the initial velocities.
  out.initial = make_initial_conditions<D>(s, out.particles, out.others ? comm : nullptr);
  bc::apply_initial_conditions<D>(out.initial, out.particles);
  auto grid = translate_mpm<D>(s);
  out.settings = std::move(grid.settings);
  out.grid_bc_source = std::move(grid.grid_bc_source);
  return out;
}

template <int D>
void check_boundary_nodes(const io::Scene& s, const std::vector<int>& grid_bc_source, const mpm::Simulation<D>& sim) {
  for (std::size_t b = 0; b < grid_bc_source.size(); ++b) {
    const int src = grid_bc_source[b];
    if (src >= 0 && sim.boundary().nodes(b).empty()) {
      std::ostringstream m;
      m << "contains no grid node (the mpm model constrains grid nodes; cell size " << sim.cell_size()
        << " m, grid lines through the body's lower faces): enlarge the box";
      throw InputError(s.file, s.boundaries[static_cast<std::size_t>(src)].key + ".region", m.str());
    }
  }
}

template <int D>
void set_initial_deformation(const std::vector<bc::InitialCondition<D>>& initial, mpm::Simulation<D>& sim) {
  for (const auto& [i, grad] : bc::initial_displacement_gradients<D>(initial, sim.particles()))
    sim.set_deformation_gradient(i, Mat<D>::Identity() + grad);
}

template MpmGridSettings<1> translate_mpm<1>(const io::Scene&);
template MpmGridSettings<2> translate_mpm<2>(const io::Scene&);
template MpmGridSettings<3> translate_mpm<3>(const io::Scene&);
template void check_boundary_nodes<1>(const io::Scene&, const std::vector<int>&, const mpm::Simulation<1>&);
template void check_boundary_nodes<2>(const io::Scene&, const std::vector<int>&, const mpm::Simulation<2>&);
template void check_boundary_nodes<3>(const io::Scene&, const std::vector<int>&, const mpm::Simulation<3>&);
template void set_initial_deformation<1>(const std::vector<bc::InitialCondition<1>>&, mpm::Simulation<1>&);
template void set_initial_deformation<2>(const std::vector<bc::InitialCondition<2>>&, mpm::Simulation<2>&);
template void set_initial_deformation<3>(const std::vector<bc::InitialCondition<3>>&, mpm::Simulation<3>&);
template MpmSetup<1> build_mpm<1>(const io::Scene&, const dist::Communicator*);
template MpmSetup<2> build_mpm<2>(const io::Scene&, const dist::Communicator*);
template MpmSetup<3> build_mpm<3>(const io::Scene&, const dist::Communicator*);

}  // namespace pdmpm::sim
