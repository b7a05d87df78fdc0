#pragma once
// Fixed-size vector and matrix aliases used everywhere; the spatial dimension
// is a template parameter (1, 2 or 3).
#include <Eigen/Dense>
#include <cstdint>

#include "solver/core/index.hpp"

namespace pdmpm {

template <int D> using Vec = Eigen::Matrix<double, D, 1>;
template <int D> using Mat = Eigen::Matrix<double, D, D>;
template <int D> using IVec = Eigen::Matrix<std::int32_t, D, 1>;

}  // namespace pdmpm
