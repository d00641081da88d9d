#pragma once
// BLAS threads under MPI. OpenBLAS starts as many threads as the machine has cores in every
// process, so `mpirun -n 2` on two cores runs four BLAS threads on two cores: measured at
// 512 k DOF (slepc, two ranks), 165 s against 124 s with one thread per rank. flexmbs shares
// the cores among the ranks on a node instead, unless the user chose a count.

namespace flexmbs::eigensolvers {

/// The number of threads the BLAS library in this process uses, or 0 if it cannot say (a BLAS
/// without a thread control, such as the reference BLAS).
int BlasThreads();

/// On every rank (collective over PETSC_COMM_WORLD, after MPI is initialised): if this node
/// runs more than one rank, neither OPENBLAS_NUM_THREADS nor OMP_NUM_THREADS is set and the
/// BLAS has a thread control, sets this process's BLAS threads to max(1, cores / ranks on this
/// node). Returns the count set, or 0 if it left the BLAS alone.
int ShareBlasThreadsAmongRanks();

}  // namespace flexmbs::eigensolvers
