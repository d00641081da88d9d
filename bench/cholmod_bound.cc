// The lower bound of a shift-invert eigen-solve, measured: one sparse Cholesky factorisation
// of K restricted to its free DOFs by CHOLMOD (supernodal, CHOLMOD's default ordering: AMD,
// then METIS where AMD's fill is high, as flexmbs' ShiftedFactorization) and the minimum
// number of single-vector solves with it. Used by reduce_bench.py (see bench/README.md).
//
//   bench_cholmod_bound K.mtx [--fixed-nodes FILE] [--solves 40] [--ordering default|amd|metis]
//
// K.mtx: `flexmbs mesh --matrix-market` output (symmetric, lower triangle, DOF 3 node + axis).
// FILE: 0-based node indices whose 3 DOF are removed (clamped). Prints one JSON object.
#include <cholmod.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench/free_dofs.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

[[noreturn]] void Fail(const std::string& message) {
  std::fprintf(stderr, "bench_cholmod_bound: %s\n", message.c_str());
  std::exit(1);
}

const char* OrderingName(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_AMD: return "amd";
    case CHOLMOD_METIS: return "metis";
    case CHOLMOD_NESDIS: return "nesdis";
    case CHOLMOD_COLAMD: return "colamd";
    default: return "other";
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string matrix_file;
  std::string fixed_file;
  std::string ordering = "default";
  int solves = 40;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--fixed-nodes" && i + 1 < argc) {
      fixed_file = argv[++i];
    } else if (arg == "--solves" && i + 1 < argc) {
      solves = std::atoi(argv[++i]);
    } else if (arg == "--ordering" && i + 1 < argc) {
      ordering = argv[++i];
    } else if (matrix_file.empty() && arg[0] != '-') {
      matrix_file = arg;
    } else {
      Fail("usage: bench_cholmod_bound K.mtx [--fixed-nodes FILE] [--solves N] [--ordering default|amd|metis]");
    }
  }
  if (matrix_file.empty()) Fail("no matrix file");

  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;

  // Read (untimed): the lower triangle as triplets.
  std::FILE* f = std::fopen(matrix_file.c_str(), "r");
  if (f == nullptr) Fail("cannot open " + matrix_file);
  cholmod_triplet* T = cholmod_read_triplet(f, &c);
  std::fclose(f);
  if (T == nullptr) Fail("cannot read " + matrix_file + " as Matrix Market");
  const long n = static_cast<long>(T->nrow);

  long n_free = 0;
  std::vector<long> new_index;
  try {
    new_index = flexmbs::bench::FreeDofIndex(n, fixed_file, &n_free);
  } catch (const std::exception& e) {
    Fail(e.what());
  }
  // Keep the entries between free DOFs, renumbered, in place; store them as the upper
  // triangle (stype = 1, as flexmbs passes K - sigma M to CHOLMOD).
  int* ti = static_cast<int*>(T->i);
  int* tj = static_cast<int*>(T->j);
  double* tx = static_cast<double*>(T->x);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < T->nnz; ++k) {
    const long r = new_index[static_cast<std::size_t>(ti[k])];
    const long s = new_index[static_cast<std::size_t>(tj[k])];
    if (r < 0 || s < 0) continue;
    ti[kept] = static_cast<int>(r < s ? r : s);
    tj[kept] = static_cast<int>(r < s ? s : r);
    tx[kept] = tx[k];
    ++kept;
  }
  T->nnz = kept;
  T->nrow = T->ncol = static_cast<std::size_t>(n_free);
  T->stype = 1;
  cholmod_sparse* A = cholmod_triplet_to_sparse(T, kept, &c);
  cholmod_free_triplet(&T, &c);
  if (A == nullptr) Fail("cannot build the free-DOF matrix");

  c.supernodal = CHOLMOD_SUPERNODAL;
  c.final_ll = 1;
  if (ordering == "amd" || ordering == "metis") {
    c.nmethods = 1;
    c.method[0].ordering = ordering == "amd" ? CHOLMOD_AMD : CHOLMOD_METIS;
  } else if (ordering != "default") {
    Fail("unknown ordering " + ordering);
  }

  auto start = std::chrono::steady_clock::now();
  cholmod_factor* L = cholmod_analyze(A, &c);
  const double analyze_seconds = Seconds(start);
  if (L == nullptr) Fail("analysis failed");
  start = std::chrono::steady_clock::now();
  cholmod_factorize(A, L, &c);
  const double factorize_seconds = Seconds(start);
  if (c.status != CHOLMOD_OK) Fail("factorisation failed with status " + std::to_string(c.status));

  // Single-vector solves, as a Lanczos iteration makes them (workspace reused).
  cholmod_dense* B = cholmod_ones(A->nrow, 1, CHOLMOD_REAL, &c);
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  start = std::chrono::steady_clock::now();
  for (int s = 0; s < solves; ++s) {
    if (!cholmod_solve2(CHOLMOD_A, L, B, nullptr, &X, nullptr, &Y, &E, &c)) Fail("solve failed");
    std::memcpy(B->x, X->x, sizeof(double) * A->nrow);  // next right-hand side: the last solution
    const double scale = 1.0 / cholmod_norm_dense(B, 2, &c);
    for (std::size_t i = 0; i < A->nrow; ++i) static_cast<double*>(B->x)[i] *= scale;
  }
  const double solve_seconds = Seconds(start);

  std::printf(
      "{\"dofs\": %ld, \"free_dofs\": %ld, \"nonzeros_upper\": %zu, \"factor_nonzeros\": %.0f, "
      "\"factor_flops\": %.6g, \"ordering\": \"%s\", \"analyze_seconds\": %.6f, \"factorize_seconds\": %.6f, "
      "\"solves\": %d, \"solve_seconds\": %.6f, \"bound_seconds\": %.6f}\n",
      n, n_free, kept, c.lnz, c.fl, OrderingName(c.method[c.selected].ordering), analyze_seconds,
      factorize_seconds, solves, solve_seconds, analyze_seconds + factorize_seconds + solve_seconds);

  cholmod_free_dense(&X, &c);
  cholmod_free_dense(&Y, &c);
  cholmod_free_dense(&E, &c);
  cholmod_free_dense(&B, &c);
  cholmod_free_factor(&L, &c);
  cholmod_free_sparse(&A, &c);
  cholmod_finish(&c);
  return 0;
}
