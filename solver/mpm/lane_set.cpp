#include "solver/mpm/lane_set.hpp"

namespace pdmpm::mpm {

std::vector<LaneVariant<GimpLanesFunction>> gimp_lanes_variants() { return lane_variants(&LaneSet::gimp); }
void gimp_lanes(const double* x_rel, const double* lp, double h, GimpLanes& out) {
  static const GimpLanesFunction chosen = choose_lane_variant(gimp_lanes_variants());
  chosen(x_rel, lp, h, out);
}

std::vector<LaneVariant<PolarLanesFunction>> polar_lanes_variants() { return lane_variants(&LaneSet::polar_log); }
unsigned polar_log_lanes(PolarLanes& lanes) {
  static const PolarLanesFunction chosen = choose_lane_variant(polar_lanes_variants());
  return chosen(lanes);
}

std::vector<LaneVariant<PlaneStressLanesFunction>> plane_stress_lanes_variants() {
  return lane_variants(&LaneSet::plane_stress);
}
unsigned plane_stress_lanes(const PlaneStressLaw& law, PlaneStressLanes& lanes) {
  static const PlaneStressLanesFunction chosen = choose_lane_variant(plane_stress_lanes_variants());
  return chosen(law, lanes);
}

std::vector<LaneVariant<DeformationLanesFunction>> deformation_lanes_variants() {
  return lane_variants(&LaneSet::advance_deformation);
}
void advance_deformation_lanes(DeformationLanes& lanes, double dt) {
  static const DeformationLanesFunction chosen = choose_lane_variant(deformation_lanes_variants());
  chosen(lanes, dt);
}

std::vector<LaneVariant<CopyLanesFunction>> copy_lanes_variants() { return lane_variants(&LaneSet::copy); }
void copy_lanes(const LaneCopy* copies, int count) {
  static const CopyLanesFunction chosen = choose_lane_variant(copy_lanes_variants());
  chosen(copies, count);
}

std::vector<LaneVariant<FractureStrainLanesFunction>> fracture_strain_lanes_variants() {
  return lane_variants(&LaneSet::fracture_strain);
}
void fracture_strain_lanes(double d0, double c, const PlaneStressLanes& law_out, unsigned needed,
                           double* fracture_strain) {
  static const FractureStrainLanesFunction chosen = choose_lane_variant(fracture_strain_lanes_variants());
  chosen(d0, c, law_out, needed, fracture_strain);
}

}  // namespace pdmpm::mpm
