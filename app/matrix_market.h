#pragma once

#include <Eigen/SparseCore>
#include <filesystem>

namespace flexmbs::app {

/// Writes the lower triangle of the symmetric matrix A as a Matrix Market file
/// ("coordinate real symmetric", 1-based indices, full double precision), atomically.
void WriteSymmetricMatrixMarket(const std::filesystem::path& path,
                                const Eigen::SparseMatrix<double>& A);

}  // namespace flexmbs::app
