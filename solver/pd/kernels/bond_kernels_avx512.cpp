// Bond loops for the avx512 instruction set (compile flags set in CMakeLists.txt).
#define PDMPM_SIMD_NS avx512
#define PDMPM_SIMD_SET kernels_avx512
#define PDMPM_SIMD_NAME "avx512"
#include "solver/pd/kernels/bond_kernels_impl.hpp"
