#include "solver/sim/j_integral_outputs.hpp"

#include "solver/core/error.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<JIntegralOutput> j_integral_outputs(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real) {
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
      if (in_ring == 0)
        throw InputError(s.file, spec.key + ".r_outer",
                         "no particle lies in the ring r_inner < |x − tip| < r_outer (is the tip inside the body, the "
                         "ring wider than Δx?)");
      out.push_back(j);
    }
  } else {
    (void)s, (void)x0, (void)n_real;
  }
  return out;
}

template std::vector<JIntegralOutput> j_integral_outputs<1>(const io::Scene&, const std::vector<Vec<1>>&, Index);
template std::vector<JIntegralOutput> j_integral_outputs<2>(const io::Scene&, const std::vector<Vec<2>>&, Index);
template std::vector<JIntegralOutput> j_integral_outputs<3>(const io::Scene&, const std::vector<Vec<3>>&, Index);

}  // namespace pdmpm::sim
