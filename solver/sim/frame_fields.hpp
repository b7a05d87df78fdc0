#pragma once
// Per-particle arrays for field frames, shared by the runs (PD, MPM, hybrid).
#include <algorithm>
#include <string>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/io/scene.hpp"
#include "solver/pd/model.hpp"
#include "solver/pd/stress.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::sim {

// True when the scene's output.fields lists `name`.
inline bool wants_field(const io::Scene& scene, const std::string& name) {
  return std::find(scene.output.fields.begin(), scene.output.fields.end(), name) != scene.output.fields.end();
}

// value(i) for i < n, a Vec<D> each, as three components per particle (zero-padded) for FieldKind::vector.
template <int D, class F>
std::vector<double> vector_field(Index n, F&& value) {
  std::vector<double> out(static_cast<std::size_t>(n) * 3, 0.0);
  for (Index i = 0; i < n; ++i) {
    const Vec<D> v = value(i);
    for (int a = 0; a < D; ++a) out[3 * i + a] = v[a];
  }
  return out;
}

// value(i) for i < n, for FieldKind::scalar.
template <class F>
std::vector<double> scalar_field(Index n, F&& value) {
  std::vector<double> out(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) out[i] = value(i);
  return out;
}

// A symmetric 3×3 stress as a field's six components, xx yy zz xy yz xz (pd::Tensor6's order).
inline pd::Tensor6 tensor6_of(const Mat<3>& s) { return {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)}; }

// value(i) for i < n, a pd::Tensor6 each, for FieldKind::tensor6.
template <class F>
std::vector<double> tensor6_field(Index n, F&& value) {
  std::vector<double> out(static_cast<std::size_t>(n) * 6);
  for (Index i = 0; i < n; ++i) {
    const pd::Tensor6 t = value(i);
    std::copy(t.begin(), t.end(), out.begin() + 6 * i);
  }
  return out;
}

// Per real particle: the PD model's own stress where it has one (plastic models),
// else the deformation-gradient stress (Hooke's law of the non-local strain).
template <int D>
std::vector<pd::Tensor6> pd_stresses(const pd::System<D>& sys, const pd::Model<D>& model) {
  if (!model.has_own_stress()) return pd::particle_stress(sys);
  const Index n = sys.particles.n_real;
  std::vector<pd::Tensor6> out(n);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) out[i] = model.own_stress(sys, i);
  return out;
}

}  // namespace pdmpm::sim
