#pragma once
// One instruction set's LaneSet (lane_set.hpp): included by lanes_<isa>.cpp with
// PDMPM_LANES_WIDTH (doubles per vector register) and PDMPM_LANES_SET set. The lane
// templates have internal linkage and each instruction set its own width, so no
// function compiled with one set's flags can stand in for another's at link time.
#include "solver/mpm/deformation_lanes_impl.hpp"
#include "solver/mpm/ductile_lanes_impl.hpp"
#include "solver/mpm/gimp_lanes_impl.hpp"
#include "solver/mpm/lane_copy_impl.hpp"
#include "solver/mpm/lane_set.hpp"
#include "solver/mpm/plane_stress_lanes_impl.hpp"
#include "solver/mpm/polar_lanes_impl.hpp"

namespace pdmpm::mpm {

const LaneSet PDMPM_LANES_SET = {
    gimp_lanes_by<PDMPM_LANES_WIDTH>,         polar_log_lanes_by<PDMPM_LANES_WIDTH>,
    plane_stress_lanes_by<PDMPM_LANES_WIDTH>, advance_deformation_by<PDMPM_LANES_WIDTH>,
    copy_lanes_by<PDMPM_LANES_WIDTH>,         fracture_strain_lanes_by<PDMPM_LANES_WIDTH>,
};

}  // namespace pdmpm::mpm
