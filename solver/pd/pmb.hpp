#pragma once
// Bond-based prototype microelastic brittle model (docs/models/pmb.md, Deryugin et al. 2023 §3–4):
// f = c ω β s μ (ξ+η)/|ξ+η| V_j, s = e/|ξ|, μ = 0 for ever once s ≥ s₀.
#include "solver/pd/model.hpp"

namespace pdmpm::pd {

template <int D>
class Pmb final : public Model<D> {
 public:
  std::string name() const override { return "pmb"; }
  void initialise(const System<D>& sys) override;
  std::int64_t compute_forces(System<D>& sys, const ForceRequest& req) override;
  double stiffness_row_sum(const System<D>& sys, Index i) const override;
  double micromodulus() const { return c_; }

 private:
  double c_ = 0.0;
};

}  // namespace pdmpm::pd
