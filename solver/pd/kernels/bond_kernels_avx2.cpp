// Bond loops for the avx2 instruction set (compile flags set in CMakeLists.txt).
#define PDMPM_SIMD_NS avx2
#define PDMPM_SIMD_SET kernels_avx2
#define PDMPM_SIMD_NAME "avx2"
#include "solver/pd/kernels/bond_kernels_impl.hpp"
