#pragma once
// How many processes a launcher (mpirun, srun) started this program as, from the
// environment it sets — known before, and without, initialising MPI.
namespace pdmpm::dist {

struct Launch {
  int processes = 1;  // 1 when started without a launcher
  int rank = 0;
};

// Reads Open MPI's OMPI_COMM_WORLD_SIZE/RANK, else PMI_SIZE/RANK (MPICH, Slurm).
Launch launch_from_environment();

}  // namespace pdmpm::dist
