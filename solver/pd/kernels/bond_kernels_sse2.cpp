// Bond loops for the sse2 instruction set (compile flags set in CMakeLists.txt).
#define PDMPM_SIMD_NS sse2
#define PDMPM_SIMD_SET kernels_sse2
#define PDMPM_SIMD_NAME "sse2"
#include "solver/pd/kernels/bond_kernels_impl.hpp"
