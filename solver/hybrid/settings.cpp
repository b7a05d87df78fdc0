#include "solver/hybrid/settings.hpp"

#include <cmath>
#include <sstream>

#include "solver/core/error.hpp"

namespace pdmpm::hybrid {
namespace {

// `v` in the interval (lo, hi) with open or closed ends, else an InputError naming key and range.
void check_range(const std::string& file, const std::string& key, double v, double lo, double hi, bool lo_open,
                 bool hi_open, const std::string& unit) {
  const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (ok) return;
  std::ostringstream m;
  m << "must be in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
  if (!unit.empty()) m << " " << unit;
  m << " (got " << v << ")";
  throw InputError(file, key, m.str());
}

}  // namespace

void Settings::validate(const std::string& file) const {
  radii.validate(file);
  if (shrink_every < 1) {
    std::ostringstream m;
    m << "must be an integer ≥ 1 (got " << shrink_every << ")";
    throw InputError(file, "hybrid.shrink_every", m.str());
  }
  check_range(file, "hybrid.revert_residual", revert_residual, 0.0, 1.0, false, false, "");
  check_range(file, "hybrid.blend_width", blend_width, 0.0, 100.0, true, false, "(units of δ)");
  const double big = 1e6;
  const std::string dx = "(units of Δx)";
  check_range(file, "hybrid.tips.damage_threshold", tips.damage_threshold, 0.0, 1.0, true, true, "");
  check_range(file, "hybrid.tips.laplacian_threshold", tips.laplacian_threshold, -big, 0.0, false, true,
              "(units of 1/Δx²)");
  check_range(file, "hybrid.tips.end_radius", tips.end_radius, 0.0, big, true, false, dx);
  check_range(file, "hybrid.tips.end_asymmetry", tips.end_asymmetry, 0.0, 1.0, false, true, "");
  check_range(file, "hybrid.tips.ridge_fraction", tips.ridge_fraction, 0.0, 1.0, false, false, "");
  check_range(file, "hybrid.tips.tip_offset", tips.tip_offset, 0.0, big, false, false, dx);
  check_range(file, "hybrid.tips.merge_radius", tips.merge_radius, 0.0, big, true, false, dx);
  check_range(file, "hybrid.tips.match_radius", tips.match_radius, 0.0, big, true, false, dx);
}

}  // namespace pdmpm::hybrid
