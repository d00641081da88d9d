#pragma once

// Products of tall, thin blocks of vectors (n rows, a few to a few hundred columns) by the
// system BLAS. Eigen's own GEMM takes 2-3x OpenBLAS's dgemm for these shapes (n = 0.1-0.5 M,
// 184 x 8 results: 153 against 88 ms for A^T B at n = 0.5 M), and the block Lanczos
// reorthogonalisation is made of them.

#include <Eigen/Core>

namespace flexmbs::eigensolvers {

/// A^T B (A: n x k, B: n x m, column-major with contiguous columns).
Eigen::MatrixXd TransposeTimes(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& B);

/// B -= A C (A: n x k, C: k x m, B: n x m).
void SubtractProduct(const Eigen::Ref<const Eigen::MatrixXd>& A,
                     const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Ref<Eigen::MatrixXd> B);

}  // namespace flexmbs::eigensolvers
