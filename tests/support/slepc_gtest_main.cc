// The main() of the MPI test programs: GoogleTest inside one SLEPc session, and a failure on
// any rank fails every rank (so mpirun's exit status says it).
#include <gtest/gtest.h>
#include <mpi.h>

#include "eigensolvers/distributed/slepc_solver.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const flexmbs::eigensolvers::SlepcSession session;
  int failed = RUN_ALL_TESTS() != 0 ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return failed;
}
