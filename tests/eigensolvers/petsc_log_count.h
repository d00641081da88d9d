#pragma once
// How often PETSc's log has seen an event on this rank: the MPI tests count factorisations and
// solves with it, against what the code reports.

#include <gtest/gtest.h>
#include <petsclog.h>
#include <petscmat.h>

namespace flexmbs::testing {

/// The count of `event` (of the Mat package, e.g. "MatCholFctrNum") on this rank so far. Logging
/// starts on the first call, so call it once before the work to be counted.
inline int LoggedEventCount(const char* event) {
  static const bool started = PetscLogDefaultBegin() == 0 && MatInitializePackage() == 0;
  EXPECT_TRUE(started);
  PetscLogEvent id = 0;
  PetscEventPerfInfo info{};
  EXPECT_EQ(PetscLogEventGetId(event, &id), 0) << event;
  EXPECT_EQ(PetscLogEventGetPerfInfo(0, id, &info), 0) << event;
  return info.count;
}

}  // namespace flexmbs::testing
