// The main() of the MPI test programs: GoogleTest inside one SLEPc session, and a failure on
// any rank fails every rank (so mpirun's exit status says it). A program that skipped a test
// on any rank and failed none exits with kSkippedExitCode, which CTest reports as skipped
// (slepc_rank_test's SKIP_RETURN_CODE): one CTest entry runs the whole program, and "passed"
// would claim the skipped test too.
#include <gtest/gtest.h>
#include <mpi.h>

#include "eigensolvers/distributed/slepc_solver.h"

namespace {
/// The exit status of a program that skipped a test and failed none (tests/CMakeLists.txt).
constexpr int kSkippedExitCode = 77;
}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const flexmbs::eigensolvers::SlepcSession session;
  int status[2] = {RUN_ALL_TESTS() != 0 ? 1 : 0, ::testing::UnitTest::GetInstance()->skipped_test_count() > 0 ? 1 : 0};
  MPI_Allreduce(MPI_IN_PLACE, status, 2, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (status[0] != 0) return 1;
  return status[1] != 0 ? kSkippedExitCode : 0;
}
