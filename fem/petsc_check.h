#pragma once
// The check of PETSc, SLEPc and MPI return codes shared by the distributed assembly and the
// SLEPc backend: a failing call is an internal error naming the call.

#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::fem {

/// Throws InternalError naming `call` if a PETSc, SLEPc or MPI call returned a non-zero error code
/// (PetscErrorCode and MPI's codes are int: the header needs no PETSc include).
inline void CheckPetsc(int code, const char* call) {
  if (code != 0) {
    throw InternalError(fmt::format("PETSc/SLEPc/MPI call {} failed with error {}", call, code));
  }
}

}  // namespace flexmbs::fem

/// Calls a PETSc or SLEPc function and checks its return code (fem::CheckPetsc).
#define FLEXMBS_PETSC(call) ::flexmbs::fem::CheckPetsc((call), #call)
