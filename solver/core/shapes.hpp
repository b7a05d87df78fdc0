#pragma once
// Closed geometric primitives in D dimensions and their ordered union/difference.
// A lattice site belongs to a body when the geometry contains it; points on a
// boundary count as inside (within a tolerance), for added and removed shapes alike.
#include <memory>
#include <string>
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::core {

template <int D>
struct Bounds {
  Vec<D> min, max;
};

template <int D>
class Shape {
 public:
  virtual ~Shape() = default;
  virtual bool contains(const Vec<D>& x, double tol) const = 0;
  virtual Bounds<D> bounds() const = 0;
  virtual std::string describe() const = 0;
};

// Axis-aligned box (rectangle in 2D, segment in 1D).
template <int D>
class Box final : public Shape<D> {
 public:
  Box(const Vec<D>& lo, const Vec<D>& hi) : lo_(lo), hi_(hi) {}
  bool contains(const Vec<D>& x, double tol) const override;
  Bounds<D> bounds() const override { return {lo_, hi_}; }
  std::string describe() const override { return "box"; }

 private:
  Vec<D> lo_, hi_;
};

// Disk in 2D, sphere in 3D, segment in 1D.
template <int D>
class Ball final : public Shape<D> {
 public:
  Ball(const Vec<D>& center, double radius) : c_(center), r_(radius) {}
  bool contains(const Vec<D>& x, double tol) const override;
  Bounds<D> bounds() const override;
  std::string describe() const override { return "ball"; }

 private:
  Vec<D> c_;
  double r_;
};

// Circular cylinder along a coordinate axis (3D only): |x⊥ − c⊥| ≤ r, lo ≤ x_axis ≤ hi.
class Cylinder final : public Shape<3> {
 public:
  Cylinder(const Vec<3>& base_center, int axis, double radius, double height)
      : c_(base_center), axis_(axis), r_(radius), h_(height) {}
  bool contains(const Vec<3>& x, double tol) const override;
  Bounds<3> bounds() const override;
  std::string describe() const override { return "cylinder"; }

 private:
  Vec<3> c_;
  int axis_;
  double r_, h_;
};

// Ordered list of shapes, each added to or removed from what came before.
template <int D>
class Geometry {
 public:
  void add(std::unique_ptr<Shape<D>> s) { parts_.push_back({std::move(s), true}); }
  void subtract(std::unique_ptr<Shape<D>> s) { parts_.push_back({std::move(s), false}); }
  bool contains(const Vec<D>& x, double tol) const;
  // Bounding box of the added shapes (what may contain a site at all).
  Bounds<D> bounds() const;
  bool empty() const;

 private:
  struct Part {
    std::unique_ptr<Shape<D>> shape;
    bool added;
  };
  std::vector<Part> parts_;
};

}  // namespace pdmpm::core
