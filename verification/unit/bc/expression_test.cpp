#include "solver/bc/expression.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdmpm::bc {
namespace {

double eval(const std::string& s, double t = 0, double x = 0, double y = 0, double z = 0) {
  return Expression::parse(s)({t, x, y, z});
}

TEST(Expression, ArithmeticAndPrecedence) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7.0);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9.0);
  EXPECT_DOUBLE_EQ(eval("2 ^ 3 ^ 2"), 512.0);  // right-associative
  EXPECT_DOUBLE_EQ(eval("-2 ^ 2"), -4.0);      // unary minus binds looser than ^
  EXPECT_DOUBLE_EQ(eval("8 / 4 / 2"), 1.0);
  EXPECT_DOUBLE_EQ(eval("1e-3 * 2"), 2e-3);
}

TEST(Expression, VariablesAndFunctions) {
  EXPECT_DOUBLE_EQ(eval("t * 2", 3.0), 6.0);
  EXPECT_DOUBLE_EQ(eval("x + y + z", 0, 1, 2, 3), 6.0);
  EXPECT_DOUBLE_EQ(eval("min(t / 2, 1)", 4.0), 1.0);
  EXPECT_DOUBLE_EQ(eval("max(-1, heaviside(t))", 0.0), 1.0);
  EXPECT_NEAR(eval("sin(pi / 2) + cos(0) + exp(0) + sqrt(4) + abs(-1) + log(1) + tanh(0) + pow(2, 3)"), 14.0, 1e-15);
  EXPECT_TRUE(Expression::parse("x*t").depends_on_position());
  EXPECT_FALSE(Expression::parse("t").depends_on_position());
}

TEST(Expression, ErrorsNameTheProblem) {
  for (const char* bad : {"", "1 +", "(1", "foo", "sin(1", "min(1)", "1 2", "max(1,2", "$"}) {
    try {
      Expression::parse(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const ExpressionError& e) {
      EXPECT_NE(std::string(e.what()).find("character"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace pdmpm::bc
