#!/usr/bin/env bash
# Distributed throughput on this machine (docs/models/distributed.md, "Scaling"): strong
# scaling of a 40³ LPS block and of a 200² MPM plate (2D, uGIMP, MUSL, J2), weak scaling of
# as much per process, with 1 and 2 processes of one OpenMP thread and, for comparison,
# one process of 2 threads.
# Interleaved repetitions; one JSON line per run, then the medians and the projection
# of docs/models/distributed.md as tables of the report's "distributed" section
# (<build>/results/data/distributed/scaling*.json). Not part of CI (timings).
# Usage: ci/mpi_scaling.sh [build-dir] [repetitions]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-3}
bin=$build/benchmarks/pdmpm_mpi_scaling
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
runs=$(mktemp)
trap 'rm -f "$runs"' EXIT
for ((r = 1; r <= reps; ++r)); do
  for method in lps mpm; do
    for mode in "" "--weak"; do
      OMP_NUM_THREADS=1 mpirun -n 1 "$bin" --method $method $mode
      OMP_NUM_THREADS=2 mpirun -n 1 --bind-to none "$bin" --method $method $mode
      OMP_NUM_THREADS=1 mpirun -n 2 "$bin" --method $method $mode
    done
  done
done | tee "$runs"
/usr/bin/python3 ci/mpi_scaling_tables.py "$runs" "$build/results/data/distributed" "$(uptime)"
