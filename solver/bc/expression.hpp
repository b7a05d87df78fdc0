#pragma once
// Small arithmetic expressions for scene files: prescribed displacements,
// velocities and loads as functions of time t and reference position x, y, z.
//   numbers, t x y z, pi, + - * / ^ (right-associative), unary minus, parentheses,
//   sin cos tan exp log sqrt abs tanh  heaviside(a) (1 for a ≥ 0)  min(a,b) max(a,b) pow(a,b)
// Example: "1e-3 * min(t / 1e-6, 1)" ramps to 1 mm over a microsecond.
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::bc {

struct ExpressionVariables {
  double t = 0.0, x = 0.0, y = 0.0, z = 0.0;
};

// The variables at a point x of a D-dimensional body at time t (unused axes 0).
template <int D>
ExpressionVariables variables_at(const Vec<D>& x, double t) {
  ExpressionVariables v;
  v.t = t;
  v.x = x[0];
  if constexpr (D > 1) v.y = x[1];
  if constexpr (D > 2) v.z = x[2];
  return v;
}

class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Expression {
 public:
  Expression() = default;
  explicit Expression(double constant);
  // Throws ExpressionError naming the position of the first problem.
  static Expression parse(const std::string& text);

  double operator()(const ExpressionVariables& v) const { return nodes_.empty() ? 0.0 : eval(root_, v); }
  const std::string& text() const { return text_; }
  bool depends_on_position() const { return uses_position_; }
  bool depends_on_time() const { return uses_time_; }

 private:
  enum class Op : unsigned char { constant, var_t, var_x, var_y, var_z, add, sub, mul, div, pow, neg, call1, call2 };
  struct Node {
    Op op;
    double value = 0.0;
    int a = -1, b = -1;
    double (*f1)(double) = nullptr;
    double (*f2)(double, double) = nullptr;
  };
  double eval(int n, const ExpressionVariables& v) const;
  friend class ExpressionParser;

  std::vector<Node> nodes_;
  int root_ = -1;
  std::string text_;
  bool uses_position_ = false;
  bool uses_time_ = false;
};

}  // namespace pdmpm::bc
