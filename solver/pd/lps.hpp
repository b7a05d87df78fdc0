#pragma once
// Ordinary state-based linear peridynamic solid (docs/models/lps.md; Silling et al. 2007,
// Le, Chan & Schwartz 2014 for 2D): two passes per evaluation,
//   θ_i = (d/m_i) Σ_j ω β |ξ| e V_j,
//   t_ij = (A θ_i ω|ξ| + B ω e) / m_i,   f_i = Σ_j (t_ij + t_ji) β V_j M_ij,
// with A, B from lps_coefficients (3D: 3K−5G, 15G; 2D: 2(κ₂−2G), 8G; 1D: 0, E).
#include "solver/pd/constants.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::pd {

template <int D>
class Lps final : public Model<D> {
 public:
  std::string name() const override { return "lps"; }
  void initialise(const System<D>& sys) override;
  void refresh(const System<D>& sys, const std::vector<Index>& changed) override;
  std::int64_t compute_forces(System<D>& sys, const ForceRequest& req) override;
  void dilatation(const System<D>& sys, std::vector<double>& theta) const override;
  double stiffness_row_sum(const System<D>& sys, Index i) const override;
  const std::vector<double>& weighted_volume() const { return m_; }
  void checkpoint(core::StateArchive& a) override;

 private:
  LpsCoefficients k_{};
  std::vector<double> m_;           // weighted volume, real + ghosts
  std::vector<double> theta_;       // dilatation of the last evaluation, real + ghosts
  std::vector<double> inv_m_;       // 1/m per particle
  std::vector<double> alpha_beta_;  // (Aθ/m, B/m) per particle, interleaved for the kernel's gather

  void set_weighted_volume(std::size_t i, double m);
};

}  // namespace pdmpm::pd
