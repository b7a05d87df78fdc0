#include "solver/bc/expression.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace pdmpm::bc {

class ExpressionParser {
 public:
  explicit ExpressionParser(const std::string& s) : s_(s) {}

  Expression run() {
    Expression e;
    e.text_ = s_;
    out_ = &e;
    e.root_ = expr();
    skip();
    if (pos_ != s_.size()) fail("unexpected '" + std::string(1, s_[pos_]) + "'");
    return e;
  }

 private:
  using Op = Expression::Op;
  using Node = Expression::Node;

  [[noreturn]] void fail(const std::string& what) const {
    throw ExpressionError("in expression \"" + s_ + "\" at character " + std::to_string(pos_ + 1) + ": " + what);
  }
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  int add(Node n) {
    out_->nodes_.push_back(n);
    return static_cast<int>(out_->nodes_.size() - 1);
  }
  int binary(Op op, int a, int b) { return add(Node{op, 0.0, a, b}); }

  int expr() {
    int left = term();
    while (true) {
      if (accept('+'))
        left = binary(Op::add, left, term());
      else if (accept('-'))
        left = binary(Op::sub, left, term());
      else
        return left;
    }
  }
  int term() {
    int left = unary();
    while (true) {
      if (accept('*'))
        left = binary(Op::mul, left, unary());
      else if (accept('/'))
        left = binary(Op::div, left, unary());
      else
        return left;
    }
  }
  int unary() {
    if (accept('-')) return add(Node{Op::neg, 0.0, unary()});
    if (accept('+')) return unary();
    return power();
  }
  int power() {
    const int base = primary();
    if (accept('^')) return binary(Op::pow, base, unary());
    return base;
  }
  int primary() {
    skip();
    if (pos_ >= s_.size()) fail("expression ends too early");
    const char c = s_[pos_];
    if (c == '(') {
      ++pos_;
      const int inner = expr();
      if (!accept(')')) fail("missing ')'");
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    fail("unexpected '" + std::string(1, c) + "'");
  }
  int number() {
    const char* begin = s_.c_str() + pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) fail("bad number");
    pos_ += static_cast<std::size_t>(end - begin);
    return add(Node{Op::constant, v});
  }
  int name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    const std::string id = s_.substr(start, pos_ - start);
    if (accept('(')) return call(id, start);
    if (id == "t") {
      out_->uses_time_ = true;
      return add(Node{Op::var_t});
    }
    if (id == "x" || id == "y" || id == "z") {
      out_->uses_position_ = true;
      return add(Node{id == "x" ? Op::var_x : id == "y" ? Op::var_y : Op::var_z});
    }
    if (id == "pi") return add(Node{Op::constant, std::numbers::pi});
    pos_ = start;
    fail("unknown name '" + id + "' (variables: t, x, y, z; constant: pi)");
  }
  int call(const std::string& id, std::size_t start) {
    using F1 = double (*)(double);
    using F2 = double (*)(double, double);
    F1 f1 = nullptr;
    F2 f2 = nullptr;
    if (id == "sin")
      f1 = [](double a) { return std::sin(a); };
    else if (id == "cos")
      f1 = [](double a) { return std::cos(a); };
    else if (id == "tan")
      f1 = [](double a) { return std::tan(a); };
    else if (id == "exp")
      f1 = [](double a) { return std::exp(a); };
    else if (id == "log")
      f1 = [](double a) { return std::log(a); };
    else if (id == "sqrt")
      f1 = [](double a) { return std::sqrt(a); };
    else if (id == "abs")
      f1 = [](double a) { return std::abs(a); };
    else if (id == "tanh")
      f1 = [](double a) { return std::tanh(a); };
    else if (id == "heaviside")
      f1 = [](double a) { return a >= 0.0 ? 1.0 : 0.0; };
    else if (id == "min")
      f2 = [](double a, double b) { return std::min(a, b); };
    else if (id == "max")
      f2 = [](double a, double b) { return std::max(a, b); };
    else if (id == "pow")
      f2 = [](double a, double b) { return std::pow(a, b); };
    else {
      pos_ = start;
      fail("unknown function '" + id + "'");
    }
    const int a = expr();
    int b = -1;
    if (f2) {
      if (!accept(',')) fail("'" + id + "' takes two arguments");
      b = expr();
    }
    if (!accept(')')) fail("missing ')' after the arguments of '" + id + "'");
    Node n{f1 ? Op::call1 : Op::call2, 0.0, a, b};
    n.f1 = f1;
    n.f2 = f2;
    return add(n);
  }

  const std::string& s_;
  std::size_t pos_ = 0;
  Expression* out_ = nullptr;
};

Expression::Expression(double constant) {
  nodes_.push_back(Node{Op::constant, constant});
  root_ = 0;
  text_ = std::to_string(constant);
}

Expression Expression::parse(const std::string& text) { return ExpressionParser(text).run(); }

double Expression::eval(int n, const ExpressionVariables& v) const {
  const Node& node = nodes_[n];
  switch (node.op) {
    case Op::constant:
      return node.value;
    case Op::var_t:
      return v.t;
    case Op::var_x:
      return v.x;
    case Op::var_y:
      return v.y;
    case Op::var_z:
      return v.z;
    case Op::add:
      return eval(node.a, v) + eval(node.b, v);
    case Op::sub:
      return eval(node.a, v) - eval(node.b, v);
    case Op::mul:
      return eval(node.a, v) * eval(node.b, v);
    case Op::div:
      return eval(node.a, v) / eval(node.b, v);
    case Op::pow:
      return std::pow(eval(node.a, v), eval(node.b, v));
    case Op::neg:
      return -eval(node.a, v);
    case Op::call1:
      return node.f1(eval(node.a, v));
    case Op::call2:
      return node.f2(eval(node.a, v), eval(node.b, v));
  }
  return 0.0;
}

}  // namespace pdmpm::bc
