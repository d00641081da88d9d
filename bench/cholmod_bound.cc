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

/// The command line (file comment).
struct Options {
  std::string matrix_file;
  std::string fixed_file;
  std::string ordering = "default";
  int solves = 40;
};

/// Reads the command line; fails with the usage on an unknown argument or no matrix file.
Options ParseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--fixed-nodes" && i + 1 < argc) {
      options.fixed_file = argv[++i];
    } else if (arg == "--solves" && i + 1 < argc) {
      options.solves = std::atoi(argv[++i]);
    } else if (arg == "--ordering" && i + 1 < argc) {
      options.ordering = argv[++i];
    } else if (options.matrix_file.empty() && arg[0] != '-') {
      options.matrix_file = arg;
    } else {
      Fail("usage: bench_cholmod_bound K.mtx [--fixed-nodes FILE] [--solves N] [--ordering default|amd|metis]");
    }
  }
  if (options.matrix_file.empty()) Fail("no matrix file");
  return options;
}

/// The Matrix Market file's lower triangle as triplets (untimed).
cholmod_triplet* ReadTriplets(const std::string& matrix_file, cholmod_common* c) {
  std::FILE* f = std::fopen(matrix_file.c_str(), "r");
  if (f == nullptr) Fail("cannot open " + matrix_file);
  cholmod_triplet* T = cholmod_read_triplet(f, c);
  std::fclose(f);
  if (T == nullptr) Fail("cannot read " + matrix_file + " as Matrix Market");
  return T;
}

/// The matrix restricted to the DOFs of the nodes not listed in fixed_file, renumbered, as its
/// upper triangle (stype = 1, as flexmbs passes K - sigma M to CHOLMOD); frees T. n_free
/// receives the free DOFs, kept the entries kept.
cholmod_sparse* FreeDofMatrix(cholmod_triplet* T, const std::string& fixed_file, cholmod_common* c,
                              long* n_free, std::size_t* kept) {
  const long n = static_cast<long>(T->nrow);
  std::vector<long> new_index;
  try {
    new_index = flexmbs::bench::FreeDofIndex(n, fixed_file, n_free);
  } catch (const std::exception& e) {
    Fail(e.what());
  }
  // Keep the entries between free DOFs, renumbered, in place.
  int* ti = static_cast<int*>(T->i);
  int* tj = static_cast<int*>(T->j);
  double* tx = static_cast<double*>(T->x);
  *kept = 0;
  for (std::size_t k = 0; k < T->nnz; ++k) {
    const long r = new_index[static_cast<std::size_t>(ti[k])];
    const long s = new_index[static_cast<std::size_t>(tj[k])];
    if (r < 0 || s < 0) continue;
    ti[*kept] = static_cast<int>(r < s ? r : s);
    tj[*kept] = static_cast<int>(r < s ? s : r);
    tx[*kept] = tx[k];
    ++*kept;
  }
  T->nnz = *kept;
  T->nrow = T->ncol = static_cast<std::size_t>(*n_free);
  T->stype = 1;
  cholmod_sparse* A = cholmod_triplet_to_sparse(T, *kept, c);
  cholmod_free_triplet(&T, c);
  if (A == nullptr) Fail("cannot build the free-DOF matrix");
  return A;
}

/// A supernodal LL^T with `ordering`: "default" (CHOLMOD's choice), "amd" or "metis".
void SetFactorization(const std::string& ordering, cholmod_common* c) {
  c->supernodal = CHOLMOD_SUPERNODAL;
  c->final_ll = 1;
  if (ordering == "amd" || ordering == "metis") {
    c->nmethods = 1;
    c->method[0].ordering = ordering == "amd" ? CHOLMOD_AMD : CHOLMOD_METIS;
  } else if (ordering != "default") {
    Fail("unknown ordering " + ordering);
  }
}

/// The measured times [s].
struct Times {
  double analyze = 0, factorize = 0, solve = 0;
};

/// A's factor, its analysis and factorisation timed into `times`.
cholmod_factor* Factorize(cholmod_sparse* A, cholmod_common* c, Times* times) {
  auto start = std::chrono::steady_clock::now();
  cholmod_factor* L = cholmod_analyze(A, c);
  times->analyze = Seconds(start);
  if (L == nullptr) Fail("analysis failed");
  start = std::chrono::steady_clock::now();
  cholmod_factorize(A, L, c);
  times->factorize = Seconds(start);
  if (c->status != CHOLMOD_OK) Fail("factorisation failed with status " + std::to_string(c->status));
  return L;
}

/// The time [s] of `solves` single-vector solves with L, as a Lanczos iteration makes them
/// (workspace reused; each right-hand side the last solution, normalised).
double TimeSolves(cholmod_sparse* A, cholmod_factor* L, int solves, cholmod_common* c) {
  cholmod_dense* B = cholmod_ones(A->nrow, 1, CHOLMOD_REAL, c);
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < solves; ++s) {
    if (!cholmod_solve2(CHOLMOD_A, L, B, nullptr, &X, nullptr, &Y, &E, c)) Fail("solve failed");
    std::memcpy(B->x, X->x, sizeof(double) * A->nrow);  // next right-hand side: the last solution
    const double scale = 1.0 / cholmod_norm_dense(B, 2, c);
    for (std::size_t i = 0; i < A->nrow; ++i) static_cast<double*>(B->x)[i] *= scale;
  }
  const double seconds = Seconds(start);
  cholmod_free_dense(&X, c);
  cholmod_free_dense(&Y, c);
  cholmod_free_dense(&E, c);
  cholmod_free_dense(&B, c);
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = ParseOptions(argc, argv);
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  cholmod_triplet* T = ReadTriplets(options.matrix_file, &c);
  const long n = static_cast<long>(T->nrow);
  long n_free = 0;
  std::size_t kept = 0;
  cholmod_sparse* A = FreeDofMatrix(T, options.fixed_file, &c, &n_free, &kept);
  SetFactorization(options.ordering, &c);
  Times times;
  cholmod_factor* L = Factorize(A, &c, &times);
  times.solve = TimeSolves(A, L, options.solves, &c);

  std::printf(
      "{\"dofs\": %ld, \"free_dofs\": %ld, \"nonzeros_upper\": %zu, \"factor_nonzeros\": %.0f, "
      "\"factor_flops\": %.6g, \"ordering\": \"%s\", \"analyze_seconds\": %.6f, \"factorize_seconds\": %.6f, "
      "\"solves\": %d, \"solve_seconds\": %.6f, \"bound_seconds\": %.6f}\n",
      n, n_free, kept, c.lnz, c.fl, OrderingName(c.method[c.selected].ordering), times.analyze,
      times.factorize, options.solves, times.solve, times.analyze + times.factorize + times.solve);

  cholmod_free_factor(&L, &c);
  cholmod_free_sparse(&A, &c);
  cholmod_finish(&c);
  return 0;
}
