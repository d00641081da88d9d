#include "app/matrix_market.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "core/atomic_file.h"

namespace flexmbs::app {

void WriteSymmetricMatrixMarket(const std::filesystem::path& path,
                                const Eigen::SparseMatrix<double>& A) {
  Eigen::Index lower_nnz = 0;
  for (Eigen::Index col = 0; col < A.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      if (it.row() >= col) ++lower_nnz;
    }
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    fmt::print(out, "%%MatrixMarket matrix coordinate real symmetric\n{} {} {}\n", A.rows(),
               A.cols(), lower_nnz);
    for (Eigen::Index col = 0; col < A.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
        if (it.row() >= col) fmt::print(out, "{} {} {:.17g}\n", it.row() + 1, col + 1, it.value());
      }
    }
  });
}

}  // namespace flexmbs::app
