#include "basis_test_support.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "fem/assembly.h"
#include "eigensolvers/shifted_factorization.h"
#include "tests/support/test_problems.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::testing {

Body AssembleBody(fem::Mesh mesh) {
  fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  return {std::move(mesh), std::move(system.stiffness), std::move(system.mass)};
}

Body MakeBox(fem::ElementType type, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
             const fem::IsotropicMaterial& material) {
  fem::Mesh mesh = fem::testing::StructuredBox(type, cells, size).mesh;
  for (fem::ElementBlock& block : mesh.blocks) block.material = material;
  return AssembleBody(std::move(mesh));
}

Body MakeBracket(fem::ElementType type, int n, int m, double a, double b, const fem::IsotropicMaterial& material) {
  const fem::Mesh box = fem::testing::StructuredBox(type, {n, m, n}, {a, b, a}).mesh;
  const double cell = a / n;
  fem::Mesh mesh;
  std::vector<int> new_index(static_cast<std::size_t>(box.num_nodes()), -1);
  std::vector<Eigen::Vector3d> kept_nodes;
  for (const fem::ElementBlock& block : box.blocks) {
    std::vector<int> columns;
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (Eigen::Index a_ = 0; a_ < block.connectivity.rows(); ++a_) centre += box.nodes.col(block.connectivity(a_, e));
      centre /= static_cast<double>(block.connectivity.rows());
      if (centre(0) > cell && centre(2) > cell) continue;
      for (Eigen::Index a_ = 0; a_ < block.connectivity.rows(); ++a_) {
        const int old = block.connectivity(a_, e);
        int& slot = new_index[static_cast<std::size_t>(old)];
        if (slot < 0) {
          slot = static_cast<int>(kept_nodes.size());
          kept_nodes.push_back(box.nodes.col(old));
        }
        columns.push_back(slot);
      }
    }
    fem::ElementBlock kept{block.type, block.region, material,
                           Eigen::Map<const fem::Connectivity>(columns.data(), block.connectivity.rows(),
                                                               static_cast<Eigen::Index>(columns.size()) /
                                                                   block.connectivity.rows()),
                           {}};
    for (Eigen::Index e = 0; e < kept.num_elements(); ++e) kept.element_ids.push_back(static_cast<std::size_t>(e) + 1);
    mesh.blocks.push_back(std::move(kept));
  }
  mesh.nodes.resize(3, static_cast<Eigen::Index>(kept_nodes.size()));
  for (std::size_t v = 0; v < kept_nodes.size(); ++v) {
    mesh.nodes.col(static_cast<Eigen::Index>(v)) = kept_nodes[v];
    mesh.node_ids.push_back(v + 1);
  }
  return AssembleBody(std::move(mesh));
}

std::vector<int> NodesAt(const fem::Mesh& mesh, int axis, double value) {
  const double tolerance = 1e-9 * std::max(1.0, mesh.nodes.cwiseAbs().maxCoeff());
  return NodesWhere(mesh, [&](const Eigen::Vector3d& x) { return std::abs(x(axis) - value) <= tolerance; });
}

std::vector<int> NodesWhere(const fem::Mesh& mesh, const std::function<bool(const Eigen::Vector3d&)>& inside) {
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (inside(mesh.nodes.col(n))) nodes.push_back(static_cast<int>(n));
  }
  return nodes;
}

const eigensolvers::Eigensolver& Spectra() {
  static const std::unique_ptr<eigensolvers::Eigensolver> solver = eigensolvers::MakeEigensolver("spectra");
  return *solver;
}

namespace {

class FactorisingItself final : public eigensolvers::Eigensolver {
 public:
  std::string_view name() const override { return "spectra"; }
  eigensolvers::EigenSolution Solve(const SparseMatrix& K, const SparseMatrix& M, const eigensolvers::EigenOptions& options) const override {
    return Spectra().Solve(K, M, options);
  }
};

}  // namespace

const eigensolvers::Eigensolver& SpectraFactorisingItself() {
  static const FactorisingItself solver;
  return solver;
}

long FactorizationsDuring(const std::function<void()>& f) {
  const long before = eigensolvers::ShiftedFactorization::NumericFactorizations();
  f();
  return eigensolvers::ShiftedFactorization::NumericFactorizations() - before;
}

void ExpectConsistentSummary(const reduction::EigensolverSummary& s) {
  EXPECT_GT(s.factorization_seconds, 0.0);
  EXPECT_GE(s.sturm_seconds, 0.0);
  EXPECT_GE(s.krylov_seconds, 0.0);
  EXPECT_LE(s.factorization_seconds + s.sturm_seconds + s.krylov_seconds, s.seconds);
  EXPECT_GE(s.factorizations, 1);
  EXPECT_GE(s.krylov_runs, 1);
  EXPECT_GE(s.restarts, 0);
  EXPECT_GE(s.operator_applications, s.krylov_runs);
}

DenseModes DenseModesOn(const SparseMatrix& K, const SparseMatrix& M, const Eigen::MatrixXd& N, double sigma) {
  const Eigen::MatrixXd Kn = N.transpose() * (K * N);
  const Eigen::MatrixXd Mn = N.transpose() * (M * N);
  const DenseEigen dense = SolveDense(Eigen::MatrixXd(0.5 * (Kn + Kn.transpose())).sparseView(),
                                      Eigen::MatrixXd(0.5 * (Mn + Mn.transpose())).sparseView(), sigma);
  return {dense.values, N * dense.vectors};
}

Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& C) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < s.size() && s(rank) > 1e-12 * s(0)) ++rank;
  return svd.matrixV().rightCols(C.cols() - rank);
}

Eigen::MatrixXd FreeDofSelection(Eigen::Index num_dofs, const std::vector<int>& clamped_nodes) {
  std::vector<bool> fixed(static_cast<std::size_t>(num_dofs), false);
  for (const int n : clamped_nodes) {
    for (int a = 0; a < 3; ++a) fixed[static_cast<std::size_t>(3 * n + a)] = true;
  }
  Eigen::Index free = 0;
  for (const bool f : fixed) free += f ? 0 : 1;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(num_dofs, free);
  Eigen::Index column = 0;
  for (Eigen::Index dof = 0; dof < num_dofs; ++dof) {
    if (!fixed[static_cast<std::size_t>(dof)]) S(dof, column++) = 1.0;
  }
  return S;
}

double Lambda(double hz) { return std::pow(2.0 * std::numbers::pi * hz, 2); }

void ExpectInputError(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown (expected one containing '" << (parts.empty() ? "" : parts[0]) << "')";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
    std::printf("[ message  ] %s\n", message.c_str());
  }
}

}  // namespace flexmbs::testing
