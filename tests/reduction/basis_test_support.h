#pragma once

// Shared by the reduced-basis tests: small bodies built in code, the serial eigensolver, dense
// references and an expectation for one-line input errors.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fem/element_type.h"
#include "fem/material.h"
#include "fem/mesh.h"
#include "eigensolvers/eigensolver.h"
#include "reduction/modal_basis.h"
#include "tests/support/test_problems.h"

namespace flexmbs::testing {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// A mesh with its consistent-mass system matrices.
struct Body {
  fem::Mesh mesh;
  SparseMatrix K;
  SparseMatrix M;
  reduction::FeModel model() const { return {K, M, mesh.nodes}; }
};
Body AssembleBody(fem::Mesh mesh);

/// A structured box of `type` (tests/fem/test_meshes.h) with `material` in every block.
Body MakeBox(fem::ElementType type, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
             const fem::IsotropicMaterial& material);

/// An L-shaped bracket: the box [0, a] x [0, b] x [0, a] of (n, m, n) structured cells with
/// the cells i >= 1 and k >= 1 removed (two legs of length a, one cell (a / n) thick, width b).
Body MakeBracket(fem::ElementType type, int n, int m, double a, double b, const fem::IsotropicMaterial& material);

/// Nodes with coordinate `axis` equal to `value` (1e-9 of the box), or inside a predicate.
std::vector<int> NodesAt(const fem::Mesh& mesh, int axis, double value);
std::vector<int> NodesWhere(const fem::Mesh& mesh, const std::function<bool(const Eigen::Vector3d&)>& inside);

/// The serial eigensolver.
const eigensolvers::Eigensolver& Spectra();
/// The serial eigensolver behind the base class's SolveFactorized, which ignores a given
/// factorisation and factorises on its own (as a backend without UsesGivenFactorization does):
/// the path on which nothing is shared, to compare the shared one with.
const eigensolvers::Eigensolver& SpectraFactorisingItself();

/// Numeric factorisations made by `f` (ShiftedFactorization::NumericFactorizations).
long FactorizationsDuring(const std::function<void()>& f);

/// Expects the parts of an eigen-solve's time to fit in its total (factorisation + Sturm +
/// Krylov <= seconds, each >= 0, the factorisation > 0) and at least one factorisation, Krylov
/// run and operator application.
void ExpectConsistentSummary(const reduction::EigensolverSummary& summary);

/// All eigenpairs of K x = lambda M x restricted to span(N) (N: num_dofs x k, independent
/// columns): dense, in shift-invert form with shift `sigma` (test_problems.h SolveDense), the
/// vectors expanded to the full DOF (x = N y) and M-orthonormal.
struct DenseModes {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};
DenseModes DenseModesOn(const SparseMatrix& K, const SparseMatrix& M, const Eigen::MatrixXd& N, double sigma);

/// An orthonormal basis (Euclidean) of the null space of the dense matrix C (rows: constraints).
Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& C);

/// The columns of the identity that select the DOF of the nodes not in `clamped_nodes`
/// (num_dofs x free).
Eigen::MatrixXd FreeDofSelection(Eigen::Index num_dofs, const std::vector<int>& clamped_nodes);

/// Eigenvalue (rad^2/s^2) of a frequency [Hz] and back.
double Lambda(double hz);

/// Expects `f` to throw InputError whose message is one line and contains every string of `parts`.
void ExpectInputError(const std::function<void()>& f, const std::vector<std::string>& parts);

}  // namespace flexmbs::testing
