#include "solver/sim/j_integral_outputs.hpp"

#include "solver/core/error.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<JIntegralOutput> j_integral_outputs(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real,
                                                const dist::Communicator* comm) {
  std::vector<JIntegralOutput> out;
  if constexpr (D == 2) {
    for (const io::JIntegralSpec& spec : s.j_integrals) {
      JIntegralOutput j;
      j.name = spec.name;
      j.domain.tip = Vec<2>(spec.tip[0], spec.tip[1]);
      j.domain.direction = Vec<2>(spec.direction[0], spec.direction[1]);
      j.domain.r_inner = spec.r_inner, j.domain.r_outer = spec.r_outer;
      j.domain.thickness = s.measure;
      Index in_ring = 0;
      for (Index i = 0; i < n_real; ++i) {
        const double r = (x0[i] - j.domain.tip).norm();
        if (r > spec.r_inner && r < spec.r_outer) ++in_ring;
      }
      if (comm) in_ring = static_cast<Index>(comm->sum(in_ring));
      if (in_ring == 0)
        throw InputError(s.file, spec.key + ".r_outer",
                         "no particle lies in the ring r_inner < |x − tip| < r_outer (is the tip inside the body, the "
                         "ring wider than Δx?)");
      out.push_back(j);
    }
  } else {
    (void)s, (void)x0, (void)n_real, (void)comm;
  }
  return out;
}

std::vector<core::JSample> gather_j_samples(std::vector<core::JSample> samples, const dist::Communicator* comm) {
  if (!comm || comm->size() == 1) return samples;
  constexpr int width = 12;  // X (2), V, ∇u (4), P (4), W
  std::vector<double> flat;
  flat.reserve(samples.size() * width);
  for (const auto& o : samples)
    flat.insert(flat.end(),
                {o.X[0], o.X[1], o.volume, o.grad_u(0, 0), o.grad_u(0, 1), o.grad_u(1, 0), o.grad_u(1, 1),
                 o.stress(0, 0), o.stress(0, 1), o.stress(1, 0), o.stress(1, 1), o.energy});
  const auto all = comm->all_gather(flat);
  samples.resize(all.size() / width);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double* v = &all[k * width];
    auto& o = samples[k];
    o.X = Vec<2>(v[0], v[1]);
    o.volume = v[2];
    o.grad_u << v[3], v[4], v[5], v[6];
    o.stress << v[7], v[8], v[9], v[10];
    o.energy = v[11];
  }
  return samples;
}

template std::vector<JIntegralOutput> j_integral_outputs<1>(const io::Scene&, const std::vector<Vec<1>>&, Index,
                                                            const dist::Communicator*);
template std::vector<JIntegralOutput> j_integral_outputs<2>(const io::Scene&, const std::vector<Vec<2>>&, Index,
                                                            const dist::Communicator*);
template std::vector<JIntegralOutput> j_integral_outputs<3>(const io::Scene&, const std::vector<Vec<3>>&, Index,
                                                            const dist::Communicator*);

}  // namespace pdmpm::sim
