// The MPM's lane functions for the avx512 instruction set, 8 doubles per vector (compile
// flags set in CMakeLists.txt; lane_set.hpp says why a file per instruction set).
#define PDMPM_LANES_WIDTH 8
#define PDMPM_LANES_SET lanes_avx512
#include "solver/mpm/lane_set_impl.hpp"
