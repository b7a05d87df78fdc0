// The MPM's lane functions for the avx2 instruction set, 4 doubles per vector (compile
// flags set in CMakeLists.txt; lane_set.hpp says why a file per instruction set).
#define PDMPM_LANES_WIDTH 4
#define PDMPM_LANES_SET lanes_avx2
#include "solver/mpm/lane_set_impl.hpp"
