// Where the time of flexmbs' eigen-solve goes: runs the "spectra" backend (the one
// `flexmbs reduce` uses by default) on K and M restricted to their free DOFs, with the options
// `flexmbs reduce` gives it for `modes: N` (EigenOptions defaults otherwise), and prints the
// EigenSolution's own accounting as one JSON object: factorisation, Sturm-count and Krylov
// seconds, numbers of factorisations, solves, Lanczos runs, restarts and refinement steps.
// For a clamped body this is the very problem `flexmbs reduce` (fixed_interface) solves:
// K_oo = G^T K G with G the selection of the free DOFs. Used by reduce_bench.py.
//
//   bench_eigensolver_split K.mtx M.mtx [--fixed-nodes FILE] [--modes 20] [--block B]
//
// --block: EigenOptions::lanczos_block_size (default 0, automatic; 1 = Spectra's Lanczos).
#include <cholmod.h>

#include <Eigen/SparseCore>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench/free_dofs.h"

#include "eigensolvers/eigensolver.h"

namespace {

[[noreturn]] void Fail(const std::string& message) {
  std::fprintf(stderr, "bench_eigensolver_split: %s\n", message.c_str());
  std::exit(1);
}

// The symmetric Matrix Market file `path` (either triangle stored) restricted to the DOFs with
// new_index >= 0, renumbered, full storage.
Eigen::SparseMatrix<double> ReadFree(const std::string& path, const std::vector<long>& new_index, long n_free,
                                     cholmod_common* c) {
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) Fail("cannot open " + path);
  cholmod_triplet* T = cholmod_read_triplet(f, c);
  std::fclose(f);
  if (T == nullptr) Fail("cannot read " + path + " as Matrix Market");
  if (T->nrow != new_index.size()) Fail(path + ": size differs from the first matrix");
  const int* ti = static_cast<const int*>(T->i);
  const int* tj = static_cast<const int*>(T->j);
  const double* tx = static_cast<const double*>(T->x);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(2 * T->nnz);
  for (std::size_t k = 0; k < T->nnz; ++k) {
    const long r = new_index[static_cast<std::size_t>(ti[k])];
    const long s = new_index[static_cast<std::size_t>(tj[k])];
    if (r < 0 || s < 0) continue;
    entries.emplace_back(r, s, tx[k]);
    if (r != s) entries.emplace_back(s, r, tx[k]);
  }
  cholmod_free_triplet(&T, c);
  Eigen::SparseMatrix<double> A(n_free, n_free);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

long ReadSize(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '%')) {
  }
  long rows = 0;
  if (std::sscanf(line.c_str(), "%ld", &rows) != 1) Fail("cannot read the size line of " + path);
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string fixed_file;
  int modes = 20;
  int block = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--fixed-nodes" && i + 1 < argc) {
      fixed_file = argv[++i];
    } else if (arg == "--modes" && i + 1 < argc) {
      modes = std::atoi(argv[++i]);
    } else if (arg == "--block" && i + 1 < argc) {
      block = std::atoi(argv[++i]);
    } else if (arg[0] != '-') {
      files.push_back(arg);
    } else {
      Fail("usage: bench_eigensolver_split K.mtx M.mtx [--fixed-nodes FILE] [--modes N] [--block B]");
    }
  }
  if (files.size() != 2) Fail("need K.mtx and M.mtx");

  const long n = ReadSize(files[0]);
  long n_free = 0;
  std::vector<long> new_index;
  try {
    new_index = flexmbs::bench::FreeDofIndex(n, fixed_file, &n_free);
  } catch (const std::exception& e) {
    Fail(e.what());
  }
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  const Eigen::SparseMatrix<double> K = ReadFree(files[0], new_index, n_free, &c);
  const Eigen::SparseMatrix<double> M = ReadFree(files[1], new_index, n_free, &c);
  cholmod_finish(&c);

  flexmbs::eigensolvers::EigenOptions options;
  options.num_modes = modes;
  options.lanczos_block_size = block;
  const auto solver = flexmbs::eigensolvers::MakeEigensolver("spectra");
  const flexmbs::eigensolvers::EigenSolution s = solver->Solve(K, M, options);
  const std::string check(flexmbs::eigensolvers::MissedModeCheckName(s.missed_mode_check));
  std::printf(
      "{\"free_dofs\": %ld, \"modes\": %ld, \"seconds\": %.6f, \"factorization_seconds\": %.6f, "
      "\"sturm_seconds\": %.6f, \"krylov_seconds\": %.6f, \"factorizations\": %d, \"operator_applications\": %d, "
      "\"krylov_runs\": %d, \"restarts\": %d, \"refinement_steps\": %d, \"missed_mode_check\": \"%s\", "
      "\"lanczos_block_size\": %d, "
      "\"lowest_hz\": %.10g, \"highest_hz\": %.10g}\n",
      n_free, static_cast<long>(s.eigenvalues.size()), s.seconds, s.factorization_seconds, s.sturm_seconds,
      s.krylov_seconds, s.factorizations, s.operator_applications, s.krylov_runs, s.restarts, s.refinement_steps,
      check.c_str(), s.lanczos_block_size, flexmbs::eigensolvers::FrequenciesHz(s)(0), flexmbs::eigensolvers::FrequenciesHz(s)(s.eigenvalues.size() - 1));
  return 0;
}
