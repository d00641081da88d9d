#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer (+ LeakSanitizer) and UndefinedBehaviorSanitizer
# (clang-14, build-sanitize/) and runs it through CTest; any sanitizer report fails its test.
#
#   scripts/check-sanitizers.sh [extra ctest arguments, e.g. -R Scene]
#
# FLEXMBS_JOBS sets build and test parallelism (default: nproc). Warnings are not errors here
# (-DFLEXMBS_WERROR=OFF): the GCC build of scripts/test.sh is the one that checks them.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
jobs=${FLEXMBS_JOBS:-$(nproc)}

# -O1 keeps the runs fast enough; no -DNDEBUG, so Eigen's bounds assertions are on too.
sanitize="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-sanitize -G Ninja \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined -fuse-ld=lld" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined -fuse-ld=lld" \
  -DFLEXMBS_WERROR=OFF -DFLEXMBS_BUILD_TESTS=ON -DFLEXMBS_BUILD_BENCH=OFF
cmake --build build-sanitize -j"$jobs"

# Every report is fatal and printed with its stack. Leaks inside third-party libraries that
# never free their globals are suppressed by library name only (scripts/lsan.supp); matching a
# library needs whole allocation stacks through code without frame pointers (Open MPI's), hence
# the slow unwinder on malloc.
# alloc_dealloc_mismatch=0: gmsh 4.8 frees with `delete` what it allocated with `new[]`
# (ClosureGen::getFaceClosurePrism, for every wedge element's reference data), and clang 14's
# ASan cannot suppress that by library; flexmbs itself has no `new[]`.
export ASAN_OPTIONS="halt_on_error=1:print_stacktrace=1:detect_leaks=1:alloc_dealloc_mismatch=0:fast_unwind_on_malloc=0:malloc_context_size=20"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
# Open MPI refuses to run as root without these (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Left out (each cannot run under the sanitizers): none so far.
excluded='^$'
ctest --test-dir build-sanitize --output-on-failure -j"$jobs" --timeout 1800 \
  -E "$excluded" "$@"
