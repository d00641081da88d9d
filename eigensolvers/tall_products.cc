#include "eigensolvers/tall_products.h"

#include <algorithm>
#include <limits>

#include "core/error.h"

extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc, std::size_t transa_length,
            std::size_t transb_length);
}

namespace flexmbs::eigensolvers {
namespace {

int BlasInt(Eigen::Index value) {
  FLEXMBS_CHECK(value >= 0 && value <= std::numeric_limits<int>::max(),
                "tall product: dimension exceeds BLAS int");
  return static_cast<int>(value);
}

// A leading dimension: at least 1, as BLAS requires even for empty matrices.
int Leading(Eigen::Index stride) { return std::max(1, BlasInt(stride)); }

}  // namespace

Eigen::MatrixXd TransposeTimes(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& B) {
  FLEXMBS_CHECK(A.rows() == B.rows(), "TransposeTimes: A and B differ in rows");
  if (A.rows() == 0 || A.cols() == 0 || B.cols() == 0)
    return Eigen::MatrixXd::Zero(A.cols(), B.cols());
  Eigen::MatrixXd C(A.cols(), B.cols());
  const int m = BlasInt(A.cols()), n = BlasInt(B.cols()), k = BlasInt(A.rows());
  const int lda = Leading(A.outerStride()), ldb = Leading(B.outerStride()), ldc = Leading(C.rows());
  const double one = 1.0, zero = 0.0;
  dgemm_("T", "N", &m, &n, &k, &one, A.data(), &lda, B.data(), &ldb, &zero, C.data(), &ldc, 1, 1);
  return C;
}

void SubtractProduct(const Eigen::Ref<const Eigen::MatrixXd>& A,
                     const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Ref<Eigen::MatrixXd> B) {
  FLEXMBS_CHECK(A.rows() == B.rows() && A.cols() == C.rows() && C.cols() == B.cols(),
                "SubtractProduct: sizes do not match");
  if (B.size() == 0 || A.cols() == 0) return;
  const int m = BlasInt(B.rows()), n = BlasInt(B.cols()), k = BlasInt(A.cols());
  const int lda = Leading(A.outerStride()), ldc = Leading(C.outerStride()),
            ldb = Leading(B.outerStride());
  const double minus_one = -1.0, one = 1.0;
  dgemm_("N", "N", &m, &n, &k, &minus_one, A.data(), &lda, C.data(), &ldc, &one, B.data(), &ldb, 1,
         1);
}

}  // namespace flexmbs::eigensolvers
