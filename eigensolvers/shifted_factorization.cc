#include "eigensolvers/shifted_factorization.h"

#include <cholmod.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"

namespace flexmbs::eigensolvers {
namespace {

std::atomic<long> numeric_factorizations{0};  // NumericFactorizations()

// A CHOLMOD view (no copy) of the upper triangle A of a symmetric matrix (stype = 1), compressed.
cholmod_sparse UpperTriangleView(Eigen::SparseMatrix<double>& A) {
  cholmod_sparse a{};
  a.nrow = static_cast<std::size_t>(A.rows());
  a.ncol = static_cast<std::size_t>(A.cols());
  a.nzmax = static_cast<std::size_t>(A.nonZeros());
  a.p = A.outerIndexPtr();
  a.i = A.innerIndexPtr();
  a.nz = nullptr;
  a.x = A.valuePtr();
  a.z = nullptr;
  a.stype = 1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

}  // namespace

struct ShiftedFactorization::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  // Reused solve workspace (cholmod_solve2 reallocates them when the shape changes).
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  bool numeric_ok = false;  // `factor` holds a valid numeric factorisation
  // The pattern `factor` was analysed for (upper triangle of K - sigma M, whatever sigma), so
  // that a new shift reuses the fill-reducing ordering and symbolic factorisation.
  std::vector<int> pattern_outer;
  std::vector<int> pattern_inner;
  Eigen::Index n = 0;
  double sigma = 0.0;
  Method method = Method::kSupernodalCholesky;
  Eigen::Index negative_pivots = 0;
  double pivot_ratio = 0.0;
  Eigen::Index failed_pivot = 0;
  double factor_nonzeros = 0.0;
  double factor_flops = 0.0;

  Impl() {
    cholmod_start(&common);
    common.print = 0;                // failures are reported through Status, not stderr
    common.error_handler = nullptr;
  }
  ~Impl() {
    FreeFactor();
    cholmod_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void FreeFactor() {
    numeric_ok = false;
    pattern_outer.clear();
    pattern_inner.clear();
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    if (x != nullptr) cholmod_free_dense(&x, &common);
    if (y != nullptr) cholmod_free_dense(&y, &common);
    if (e != nullptr) cholmod_free_dense(&e, &common);
  }

  // The symbolic factorisation (fill-reducing ordering) of `a`, kept while the pattern of A and
  // the method stay the same, so that a new shift reuses it.
  void Analyze(cholmod_sparse* a, const Eigen::SparseMatrix<double>& A, Method new_method) {
    const auto outer = std::span<const int>(A.outerIndexPtr(), static_cast<std::size_t>(A.cols()) + 1);
    const auto inner = std::span<const int>(A.innerIndexPtr(), static_cast<std::size_t>(A.nonZeros()));
    if (factor != nullptr && method == new_method && std::ranges::equal(outer, pattern_outer) &&
        std::ranges::equal(inner, pattern_inner)) {
      return;
    }
    FreeFactor();
    method = new_method;
    factor = cholmod_analyze(a, &common);
    if (factor == nullptr) {
      if (common.status == CHOLMOD_OUT_OF_MEMORY || common.status == CHOLMOD_TOO_LARGE) throw std::bad_alloc();
      throw InternalError("CHOLMOD analysis failed with status " + std::to_string(common.status));
    }
    pattern_outer.assign(outer.begin(), outer.end());
    pattern_inner.assign(inner.begin(), inner.end());
    factor_nonzeros = common.lnz;
    factor_flops = common.fl;
  }

  // The pivot statistics of a successful numeric factorisation: the pivot ratio, and for
  // L D L^T the number of negative pivots (the inertia).
  void RecordPivots() {
    if (method == Method::kSupernodalCholesky) {
      pivot_ratio = cholmod_rcond(factor, &common);  // (min L_kk / max L_kk)^2 for L L^T
      return;
    }
    // Simplicial L D L^T: column j of L starts with D_jj.
    const int* p = static_cast<const int*>(factor->p);
    const double* values = static_cast<const double*>(factor->x);
    double dmin = std::numeric_limits<double>::infinity();
    double dmax = 0.0;
    for (std::size_t j = 0; j < factor->n; ++j) {
      const double djj = values[p[j]];
      if (djj < 0.0) ++negative_pivots;
      dmin = std::min(dmin, std::abs(djj));
      dmax = std::max(dmax, std::abs(djj));
    }
    pivot_ratio = dmax > 0.0 ? dmin / dmax : 0.0;
  }
};

ShiftedFactorization::ShiftedFactorization() : impl_(std::make_unique<Impl>()) {}
ShiftedFactorization::~ShiftedFactorization() = default;
ShiftedFactorization::ShiftedFactorization(ShiftedFactorization&&) noexcept = default;
ShiftedFactorization& ShiftedFactorization::operator=(ShiftedFactorization&&) noexcept = default;

ShiftedFactorization::Status ShiftedFactorization::Factorize(const Eigen::SparseMatrix<double>& K,
                                                             const Eigen::SparseMatrix<double>& M,
                                                             double sigma, Method method) {
  FLEXMBS_CHECK(K.rows() == K.cols() && M.rows() == K.rows() && M.cols() == K.cols(),
                "ShiftedFactorization: K and M must be square and of equal size");
  Impl& d = *impl_;
  d.numeric_ok = false;
  d.n = K.rows();
  d.sigma = sigma;
  d.negative_pivots = 0;
  d.pivot_ratio = 0.0;
  d.failed_pivot = d.n;

  // Upper triangle of A = K - sigma M in compressed column storage (CHOLMOD stype = 1). The
  // difference keeps the union pattern of K and M for every sigma, zero included.
  Eigen::SparseMatrix<double> A = Eigen::SparseMatrix<double>(K - sigma * M).triangularView<Eigen::Upper>();
  A.makeCompressed();
  cholmod_sparse a = UpperTriangleView(A);

  cholmod_common& c = d.common;
  c.supernodal = method == Method::kSupernodalCholesky ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  c.final_ll = method == Method::kSupernodalCholesky ? 1 : 0;
  d.Analyze(&a, A, method);
  numeric_factorizations.fetch_add(1, std::memory_order_relaxed);
  cholmod_factorize(&a, d.factor, &c);
  if (c.status == CHOLMOD_OUT_OF_MEMORY || c.status == CHOLMOD_TOO_LARGE) {
    d.FreeFactor();
    throw std::bad_alloc();
  }
  if (c.status < CHOLMOD_OK) {
    const int status = c.status;
    d.FreeFactor();
    throw InternalError("CHOLMOD factorisation failed with status " + std::to_string(status));
  }
  if (c.status == CHOLMOD_NOT_POSDEF || d.factor->minor < d.factor->n) {
    d.failed_pivot = static_cast<Eigen::Index>(d.factor->minor);  // the symbolic part stays for a retry
    return method == Method::kSupernodalCholesky ? Status::kNotPositiveDefinite : Status::kSingular;
  }
  d.RecordPivots();
  d.numeric_ok = true;
  return Status::kOk;
}

bool ShiftedFactorization::ok() const { return impl_->numeric_ok; }
Eigen::Index ShiftedFactorization::rows() const { return impl_->n; }
double ShiftedFactorization::sigma() const { return impl_->sigma; }
ShiftedFactorization::Method ShiftedFactorization::method() const { return impl_->method; }
Eigen::Index ShiftedFactorization::NegativePivots() const { return impl_->negative_pivots; }
double ShiftedFactorization::PivotRatio() const { return impl_->pivot_ratio; }
Eigen::Index ShiftedFactorization::FailedPivot() const { return impl_->failed_pivot; }
double ShiftedFactorization::FactorNonzeros() const { return impl_->factor_nonzeros; }
double ShiftedFactorization::FactorFlops() const { return impl_->factor_flops; }
long ShiftedFactorization::NumericFactorizations() { return numeric_factorizations.load(std::memory_order_relaxed); }

void ShiftedFactorization::Solve(const double* B, double* X, Eigen::Index num_rhs) const {
  Impl& d = *impl_;
  FLEXMBS_CHECK(d.numeric_ok, "ShiftedFactorization::Solve without a valid factorisation");
  if (num_rhs <= 0 || d.n == 0) return;
  cholmod_dense b{};
  b.nrow = static_cast<std::size_t>(d.n);
  b.ncol = static_cast<std::size_t>(num_rhs);
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<double*>(B);  // read only: CHOLMOD's B is not const-qualified
  b.z = nullptr;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  const int ok = cholmod_solve2(CHOLMOD_A, d.factor, &b, nullptr, &d.x, nullptr, &d.y, &d.e,
                                &d.common);
  if (!ok || d.x == nullptr) {
    if (d.common.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    throw InternalError("CHOLMOD solve failed with status " + std::to_string(d.common.status));
  }
  std::memcpy(X, d.x->x, sizeof(double) * b.nzmax);
}

Eigen::MatrixXd ShiftedFactorization::Solve(const Eigen::MatrixXd& B) const {
  FLEXMBS_CHECK(B.rows() == rows(), "ShiftedFactorization::Solve: wrong right-hand side size");
  Eigen::MatrixXd X(B.rows(), B.cols());
  Solve(B.data(), X.data(), B.cols());
  return X;
}

}  // namespace flexmbs::eigensolvers
