// The MPM's lane functions for the sse2 instruction set, 2 doubles per vector (compile
// flags set in CMakeLists.txt; lane_set.hpp says why a file per instruction set).
#define PDMPM_LANES_WIDTH 2
#define PDMPM_LANES_SET lanes_sse2
#include "solver/mpm/lane_set_impl.hpp"
