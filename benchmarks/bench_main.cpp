// main() of pdmpm_bench: Google Benchmark's, plus the build's provenance in the
// JSON "context" (compiler, flags, git commit, SIMD level), which the report shows
// next to the CPU that Google Benchmark records itself.
#include <benchmark/benchmark.h>

#include "solver/pd/kernels/bond_kernels.hpp"
#include "solver/core/build_info.hpp"

int main(int argc, char** argv) {
  benchmark::AddCustomContext("pdmpm_compiler", pdmpm::build_info::compiler());
  benchmark::AddCustomContext("pdmpm_flags", pdmpm::build_info::flags());
  benchmark::AddCustomContext("pdmpm_git_sha", pdmpm::build_info::git_sha());
  benchmark::AddCustomContext("pdmpm_simd", pdmpm::pd::kernels::simd_level());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
