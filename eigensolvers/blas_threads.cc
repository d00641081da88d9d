#include "eigensolvers/blas_threads.h"

#include <dlfcn.h>
#include <petscsys.h>

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "core/error.h"

namespace flexmbs::eigensolvers {
namespace {

// OpenBLAS's thread control, looked up at run time: the BLAS behind libblas.so.3 is chosen by
// Debian's alternatives, and the reference BLAS has none.
using GetThreads = int (*)();
using SetThreads = void (*)(int);

GetThreads OpenBlasGet() { return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads")); }
SetThreads OpenBlasSet() { return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")); }

}  // namespace

int BlasThreads() {
  const GetThreads get = OpenBlasGet();
  return get ? get() : 0;
}

int ShareBlasThreadsAmongRanks() {
  MPI_Comm node = MPI_COMM_NULL;
  FLEXMBS_CHECK(MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) == MPI_SUCCESS,
                "MPI_Comm_split_type failed");
  int ranks_on_node = 1;
  MPI_Comm_size(node, &ranks_on_node);
  MPI_Comm_free(&node);
  const SetThreads set = OpenBlasSet();
  if (ranks_on_node == 1 || set == nullptr || std::getenv("OPENBLAS_NUM_THREADS") != nullptr || std::getenv("OMP_NUM_THREADS") != nullptr) {
    return 0;
  }
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::max(1, cores / ranks_on_node);
  set(threads);
  return threads;
}

}  // namespace flexmbs::eigensolvers
