# Sourced by scripts/check-sanitizers.sh and scripts/fuzz.sh: the clang-14 tree both configure,
# and the sanitizer run-time settings both use. Not a script of its own.

# configure_clang_tree DIR "COMPILE FLAGS" [cmake arguments ...]: configures DIR (Ninja,
# clang-14, -O1 with line tables, no -DNDEBUG so Eigen's bounds assertions are on, lld) with the
# sanitizer flags given. Warnings are not errors here (-DFLEXMBS_WERROR=OFF): the GCC build of
# scripts/test.sh is the one that checks them.
configure_clang_tree() {
  local dir=$1 flags=$2
  shift 2
  cmake -S . -B "$dir" -G Ninja \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined -fuse-ld=lld" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined -fuse-ld=lld" \
    -DFLEXMBS_WERROR=OFF -DFLEXMBS_BUILD_BENCH=OFF "$@"
}

# export_sanitizer_options ROOT [extra ASAN_OPTIONS]: every report fatal and printed with its
# stack; leaks inside third-party libraries suppressed by library name only (ROOT/scripts/lsan.supp).
# allocator_may_return_null=1: a damaged HDF5 file makes HDF5 ask malloc for what a size field
# claims (1 TiB and more, found by fuzz_results_reader); a release build's malloc returns null
# and HDF5 reports an error (an InputError), where ASan would abort instead. C++'s new still
# reports: flexmbs has no malloc of its own.
export_sanitizer_options() {
  local root=$1 extra=${2:-}
  export ASAN_OPTIONS="halt_on_error=1:print_stacktrace=1:detect_leaks=1:allocator_may_return_null=1${extra:+:$extra}"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
}
