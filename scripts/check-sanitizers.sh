#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer (+ LeakSanitizer) and UndefinedBehaviorSanitizer
# (clang-14, build-sanitize/) and runs it through CTest; any sanitizer report fails its test.
#
#   scripts/check-sanitizers.sh [extra ctest arguments, e.g. -R Scene]
#
# FLEXMBS_JOBS sets build and test parallelism (default: nproc). The clang tree and the
# sanitizer options are scripts/clang-env.sh's.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
jobs=${FLEXMBS_JOBS:-$(nproc)}

source scripts/clang-env.sh
configure_clang_tree build-sanitize "-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
  -DFLEXMBS_BUILD_TESTS=ON
cmake --build build-sanitize -j"$jobs"

# alloc_dealloc_mismatch=0: gmsh 4.8 frees with `delete` what it allocated with `new[]`
# (ClosureGen::getFaceClosurePrism, for every wedge element's reference data), and clang 14's
# ASan cannot suppress that by library; flexmbs itself has no `new[]`.
common_options="alloc_dealloc_mismatch=0:malloc_context_size=20"
# The corruption tests flip every 7th of their positions (tests/integrity/corruption_test.cc):
# all of them took 19.5 min for the body alone under ASan.
export FLEXMBS_FLIP_EVERY=7
# Open MPI refuses to run as root without these (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Left out (each cannot run under the sanitizers): none so far.
excluded='^$'
run_ctest() {
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs" --timeout 1800 -E "$excluded" "$@"
}
# Two runs, by the label `mpi` (the executables that start Open MPI, PETSc or SLEPc). Matching
# Open MPI's leaks to scripts/lsan.supp needs whole allocation stacks through its code, built
# without frame pointers: the slow unwinder on every allocation (fast_unwind_on_malloc=0), which
# makes Eigen-heavy tests 20-50x slower (docs/building.md). Everything else keeps the fast one.
export_sanitizer_options "$root" "$common_options"
status=0
run_ctest -LE mpi "$@" || status=$?
export_sanitizer_options "$root" "$common_options:fast_unwind_on_malloc=0"
run_ctest -L mpi "$@" || status=$?
exit "$status"
