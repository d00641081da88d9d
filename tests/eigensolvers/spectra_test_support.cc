#include "tests/eigensolvers/spectra_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "eigensolvers/shifted_factorization.h"
#include "fem/assembly.h"
#include "tests/support/eigen_contract.h"

namespace flexmbs::eigensolvers::spectra_test {
namespace {

using flexmbs::testing::HexBox;
using flexmbs::testing::kClusterTolerance;
using flexmbs::testing::kOrthonormalityBound;
using flexmbs::testing::kResidualBound;
using flexmbs::testing::LargestPrincipalAngleSine;
using flexmbs::testing::NodesOnPlane;

// The solver's round-off floors against the test's (other summation orders), relative: measured
// 6.5e-12.
constexpr double kFloorRoundOff = 5e-11;
// Eigenvalue agreement with the dense solver, relative to max(|lambda|, first elastic
// lambda). The dense reference is in shift-invert form, accurate relative to each low
// eigenvalue (test_problems.h); measured deviations are 1e-12 .. 3e-11, this is the
// contract's 1e-8.
constexpr double kDenseAgreement = 1e-8;

// The residuals and round-off floors of EigenSolution's definition (eigensolver.h), computed
// here from K and M with Eigen's own sparse products, not with the solver's functions
// (ComputeResiduals, MOrthonormalityError), so that a wrong definition there cannot hide a bad pair.
struct TestResiduals {
  Eigen::VectorXd relative, floor;
};
TestResiduals ResidualsFromKAndM(const SparseMatrix& K, const SparseMatrix& M, const EigenSolution& s) {
  const SparseMatrix K_abs = K.cwiseAbs(), M_abs = M.cwiseAbs();
  const double zero_eigenvalue = kZeroEigenvalue * K.diagonal().sum() / M.diagonal().sum();
  TestResiduals r{Eigen::VectorXd(s.eigenvalues.size()), Eigen::VectorXd(s.eigenvalues.size())};
  for (Eigen::Index j = 0; j < s.eigenvalues.size(); ++j) {
    const double lambda = s.eigenvalues(j);
    const Eigen::VectorXd phi = s.modes.col(j), K_phi = K * phi, M_phi = M * phi;
    const Eigen::VectorXd abs_phi = phi.cwiseAbs();
    const double rigid_scale = std::abs(lambda) <= zero_eigenvalue ? std::abs(s.shift) * M_phi.norm() : 0.0;
    const double d = std::max({K_phi.norm(), std::abs(lambda) * M_phi.norm(), rigid_scale,
                               std::numeric_limits<double>::min()});
    r.relative(j) = (K_phi - lambda * M_phi).norm() / d;
    r.floor(j) = std::numeric_limits<double>::epsilon() *
                 (K_abs * abs_phi + std::abs(lambda) * (M_abs * abs_phi)).norm() / d;
  }
  return r;
}

}  // namespace

const std::unique_ptr<Eigensolver>& Spectra() {
  static const std::unique_ptr<Eigensolver> solver = MakeEigensolver("spectra");
  return solver;
}

double FreeFreeShift(const Problem& p) { return FreeBodyShift(p.K, p.M); }

Problem Assemble(fem::Mesh mesh) {
  fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  return {std::move(mesh), std::move(system.stiffness), std::move(system.mass)};
}

void ExpectContract(const SparseMatrix& K, const SparseMatrix& M, const EigenSolution& s, bool strict) {
  ASSERT_EQ(s.modes.cols(), s.eigenvalues.size());
  ASSERT_EQ(s.relative_residuals.size(), s.eigenvalues.size());
  ASSERT_EQ(s.residual_floors.size(), s.eigenvalues.size());
  for (Eigen::Index j = 1; j < s.eigenvalues.size(); ++j) EXPECT_LE(s.eigenvalues(j - 1), s.eigenvalues(j));
  const TestResiduals residuals = ResidualsFromKAndM(K, M, s);
  for (Eigen::Index j = 0; j < residuals.relative.size(); ++j) {
    if (strict) {
      EXPECT_LE(residuals.relative(j), kResidualBound) << "mode " << j;
      EXPECT_LE(residuals.floor(j), kResidualBound) << "mode " << j;  // the bound is attainable
    } else {
      EXPECT_LE(residuals.relative(j), std::max(kResidualBound, kResidualFloorFactor * residuals.floor(j)))
          << "mode " << j;
    }
    // The backend multiplies M through M_s (eigensolvers/mass_operator.h), a summation order of its
    // own: the two residuals of one pair may differ by the round-off of computing them.
    EXPECT_NEAR(residuals.relative(j), s.relative_residuals(j), residuals.floor(j)) << "mode " << j;
    EXPECT_NEAR(residuals.floor(j), s.residual_floors(j), kFloorRoundOff * residuals.floor(j)) << "mode " << j;
  }
  const Eigen::MatrixXd gram = s.modes.transpose() * (M * s.modes);
  const double orthonormality = (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
  EXPECT_LE(orthonormality, kOrthonormalityBound);
  // The same Gram matrix summed in another order (M_s): equal to round-off.
  EXPECT_NEAR(s.orthonormality_error, orthonormality, 1e-14);
}

void ExpectMatchesDense(const SparseMatrix& M, const EigenSolution& s, const flexmbs::testing::DenseEigen& dense,
                        double lambda_ref) {
  const Eigen::Index n = s.eigenvalues.size();
  ASSERT_LE(n, dense.values.size());
  double max_deviation = 0.0;
  double max_sine = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double deviation =
        std::abs(s.eigenvalues(j) - dense.values(j)) / std::max(std::abs(dense.values(j)), lambda_ref);
    max_deviation = std::max(max_deviation, deviation);
    EXPECT_LE(deviation, kDenseAgreement)
        << "mode " << j << ": " << s.eigenvalues(j) << " vs dense " << dense.values(j);
  }
  const auto same = [&](double a, double b) {
    return std::abs(a - b) <= kClusterTolerance * std::max({std::abs(a), std::abs(b), lambda_ref});
  };
  for (Eigen::Index begin = 0; begin < n;) {
    Eigen::Index end = begin + 1;
    while (end < dense.values.size() && same(dense.values(end - 1), dense.values(end))) ++end;
    if (end > n) break;  // a cluster cut by the last returned mode: its subspace is not unique
    const double sine = LargestPrincipalAngleSine(M, s.modes.middleCols(begin, end - begin),
                                                  dense.vectors.middleCols(begin, end - begin));
    EXPECT_LE(sine, kSubspaceAgreement) << "cluster of modes " << begin << ".." << end - 1;
    max_sine = std::max(max_sine, sine);
    begin = end;
  }
  std::printf("[ numbers  ] vs dense: max eigenvalue deviation %.1e, max principal-angle sine %.1e\n", max_deviation,
              max_sine);
}

void Report(const char* what, const EigenSolution& s) {
  std::printf("[ numbers  ] %s: %td modes, max residual %.2e, orthonormality %.2e, %d factorisations, %d solves, "
              "%d Lanczos runs, %d restarts, %d refinements, %.3f s\n",
              what, s.eigenvalues.size(), s.relative_residuals.size() ? s.relative_residuals.maxCoeff() : 0.0,
              s.orthonormality_error, s.factorizations, s.operator_applications, s.krylov_runs, s.restarts,
              s.refinement_steps, s.seconds);
}

Cantilever MakeCantilever(const fem::IsotropicMaterial& left, const fem::IsotropicMaterial& right) {
  Problem p = Assemble(HexBox({12, 3, 3}, {0.6, 0.05, 0.04}, left, right, 0.3));
  reduction::FreeDofMap map = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), NodesOnPlane(p.mesh, 0, 0.0));
  SparseMatrix K = map.Restrict(p.K);
  SparseMatrix M = map.Restrict(p.M);
  return {std::move(p), std::move(map), std::move(K), std::move(M)};
}

}  // namespace flexmbs::eigensolvers::spectra_test
