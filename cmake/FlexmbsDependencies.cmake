# Finds every third-party library and exposes each as an imported target.
# How each is found on Debian 12, and the pitfalls met, is documented in docs/building.md.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(fmt REQUIRED)
find_package(Threads REQUIRED)
find_package(OpenSSL 3 REQUIRED COMPONENTS Crypto)
find_package(PkgConfig REQUIRED)

# gmsh: no CMake config and no .pc on Debian; header and library by hand.
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
add_library(flexmbs_ext_gmsh INTERFACE)
target_include_directories(flexmbs_ext_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(flexmbs_ext_gmsh INTERFACE ${GMSH_LIBRARY})
add_library(ext::gmsh ALIAS flexmbs_ext_gmsh)

# PETSc (and SLEPc) through pkg-config; the .pc files lack MPI, so link MPI::MPI_C too.
find_package(MPI REQUIRED COMPONENTS C)
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc)
add_library(flexmbs_ext_petsc INTERFACE)
target_link_libraries(flexmbs_ext_petsc INTERFACE PkgConfig::PETSC MPI::MPI_C)
# <mpi.h> in C++ would pull in the deprecated MPI C++ bindings (libmpi_cxx): only C is used.
target_compile_definitions(flexmbs_ext_petsc INTERFACE OMPI_SKIP_MPICXX=1 MPICH_SKIP_MPICXX=1)
add_library(ext::petsc ALIAS flexmbs_ext_petsc)
pkg_check_modules(SLEPC REQUIRED IMPORTED_TARGET SLEPc)
add_library(flexmbs_ext_slepc INTERFACE)
target_link_libraries(flexmbs_ext_slepc INTERFACE PkgConfig::SLEPC flexmbs_ext_petsc)
add_library(ext::slepc ALIAS flexmbs_ext_slepc)

# Eigen's headers trigger -Wshadow and friends: include them as system headers.
get_target_property(_eigen_inc Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
set_target_properties(Eigen3::Eigen PROPERTIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_eigen_inc}")

if(FLEXMBS_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(FLEXMBS_BUILD_BENCH)
  find_package(benchmark QUIET)
endif()

# CHOLMOD (SuiteSparse): no CMake config and no .pc on Debian; header (under suitesparse/)
# and library by hand. Sources include <cholmod.h>.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(ext::cholmod INTERFACE IMPORTED)
target_include_directories(ext::cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(ext::cholmod INTERFACE ${CHOLMOD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY})

# Spectra (header-only): Debian ships a CMake config; fall back to the header by hand.
find_package(Spectra 1.0 QUIET CONFIG)
if(TARGET Spectra::Spectra)
  get_target_property(_spectra_inc Spectra::Spectra INTERFACE_INCLUDE_DIRECTORIES)
  if(_spectra_inc)
    set_target_properties(Spectra::Spectra PROPERTIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_spectra_inc}")
  endif()
else()
  find_path(SPECTRA_INCLUDE_DIR Spectra/SymGEigsShiftSolver.h REQUIRED)
  add_library(Spectra::Spectra INTERFACE IMPORTED)
  target_include_directories(Spectra::Spectra SYSTEM INTERFACE ${SPECTRA_INCLUDE_DIR})
  target_link_libraries(Spectra::Spectra INTERFACE Eigen3::Eigen)
endif()

# HDF5: the Open MPI build through pkg-config, the one PETSc already links (see docs/building.md);
# CMake's FindHDF5 would mix the serial and parallel libraries. The .pc also gives Open MPI's
# include directories, which <hdf5.h> needs for <mpi.h>. Include directories of an imported
# target are SYSTEM for its consumers, so -Werror builds stay clean.
pkg_check_modules(FLEXMBS_HDF5 REQUIRED IMPORTED_TARGET hdf5-openmpi)
add_library(ext::hdf5 INTERFACE IMPORTED)
target_link_libraries(ext::hdf5 INTERFACE PkgConfig::FLEXMBS_HDF5)

# xxHash (XXH3-128, the content digest of bodies and results: docs/sid.md): pkg-config.
pkg_check_modules(FLEXMBS_XXHASH REQUIRED IMPORTED_TARGET libxxhash)
add_library(ext::xxhash INTERFACE IMPORTED)
target_link_libraries(ext::xxhash INTERFACE PkgConfig::FLEXMBS_XXHASH)

# SUNDIALS 6 (ARKODE): CMake config. libsundials_arkode holds the serial N_Vector and the dense
# matrix and linear solver too; the targets are listed for clarity. A SUNContext comes first.
find_package(SUNDIALS 6 REQUIRED CONFIG)
add_library(ext::sundials INTERFACE IMPORTED)
target_link_libraries(ext::sundials INTERFACE SUNDIALS::arkode_shared SUNDIALS::nvecserial_shared
                      SUNDIALS::sunmatrixdense_shared SUNDIALS::sunlinsoldense_shared)

# The system BLAS (dgemm for tall, thin block products, eigensolvers/tall_products.h): libblas.so.3,
# which Debian's alternatives point at OpenBLAS (libopenblas0-pthread).
find_library(BLAS_LIBRARY blas REQUIRED)
add_library(ext::blas INTERFACE IMPORTED)
target_link_libraries(ext::blas INTERFACE ${BLAS_LIBRARY})

# MUMPS's own C interface (the MPI build PETSc links) for the substructured factorisation's
# sequential interior solves with Schur complements, METIS for their ordering, and LAPACK for its
# dense interface matrix.
find_path(MUMPS_INCLUDE_DIR dmumps_c.h REQUIRED)
find_library(DMUMPS_LIBRARY dmumps REQUIRED)
find_library(LAPACK_LIBRARY lapack REQUIRED)
find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
add_library(ext::mumps INTERFACE IMPORTED)
target_include_directories(ext::mumps SYSTEM INTERFACE ${MUMPS_INCLUDE_DIR} ${METIS_INCLUDE_DIR})
target_link_libraries(ext::mumps INTERFACE ${DMUMPS_LIBRARY} ${LAPACK_LIBRARY} ${METIS_LIBRARY} MPI::MPI_C)

# Siconos numerics 4.4 (the complementarity peer, contact/complementarity/siconos_solvers.cc):
# Debian's CMake config is broken, so header and library by hand. Its headers include each other
# as "NumericsFwd.h" and "SiconosConfig.h": both directories go on the (SYSTEM) include path.
find_path(SICONOS_NUMERICS_INCLUDE_DIR LinearComplementarityProblem.h PATH_SUFFIXES siconos/numerics REQUIRED)
find_path(SICONOS_CONFIG_INCLUDE_DIR SiconosConfig.h PATH_SUFFIXES siconos REQUIRED)
find_library(SICONOS_NUMERICS_LIBRARY siconos_numerics REQUIRED)
add_library(ext::siconos INTERFACE IMPORTED)
target_include_directories(ext::siconos SYSTEM INTERFACE ${SICONOS_NUMERICS_INCLUDE_DIR} ${SICONOS_CONFIG_INCLUDE_DIR})
target_link_libraries(ext::siconos INTERFACE ${SICONOS_NUMERICS_LIBRARY})

# FCL 0.7 (the broad-phase peer of bench/pcm_bench.cc): Debian's CMake config (target `fcl`); its
# .pc file would add -std=c++11. Headers as SYSTEM, as Eigen's.
find_package(fcl REQUIRED)
add_library(ext::fcl INTERFACE IMPORTED)
target_link_libraries(ext::fcl INTERFACE fcl)
get_target_property(_fcl_inc fcl INTERFACE_INCLUDE_DIRECTORIES)
set_target_properties(fcl PROPERTIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_fcl_inc}")
