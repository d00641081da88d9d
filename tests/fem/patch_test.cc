// Patch test (Irons; Zienkiewicz & Taylor, The Finite Element Method, vol. 1, ch. 10): on a mesh
// with randomly moved interior nodes, a linear displacement u = a + B x prescribed on the
// boundary is reproduced exactly inside, and leaves no force at interior nodes. Also: rigid-body
// fields are in the null space of K.

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// Round-off of a sparse solve of ~1000 unknowns with cond(K_ii) ~ 1e3..1e4 (fine structured
// meshes): well below 1e-10 relative.
constexpr double kPatchTol = 1e-10;
// K u summed row by row: the residual is round-off relative to sum_j |K_ij u_j|.
constexpr double kForceTol = 1e-10;
// Interior corner nodes move by up to 20 % of the cell size per axis; for the curved variant
// interior mid-side nodes also leave their edge by up to 8 %: all Jacobians stay positive.
constexpr double kCornerFraction = 0.2;
constexpr double kCurveFraction = 0.08;
// u^T K u of a linear field is a sum of large terms that cancel (the field's translation part
// B t is ~|x| / h = 10x larger than its elastic part): round-off ~1e-14 relative, x 100.
constexpr double kEnergyTol = 1e-12;
// The patch: a 1.0 x 0.8 x 0.6 m box.
const Eigen::Vector3d kSize(1.0, 0.8, 0.6);

struct PatchCase {
  ElementType type;
  bool curved;  ///< quadratic elements with interior mid-side nodes off their straight edges
  ElementType second_type = type;  ///< a mixed mesh: the cells with x index >= 1 are of this type
};

// Test name suffix of a case: "hex20Curved", "hex8AndWedge6".
std::string CaseName(const PatchCase& c) {
  std::string name(Traits(c.type).name);
  if (c.second_type != c.type) name += "And" + std::string(Traits(c.second_type).name);
  return name + (c.curved ? "Curved" : "");
}
// gtest prints a case by its name rather than its bytes.
void PrintTo(const PatchCase& c, std::ostream* os) { *os << CaseName(c); }

// Nodal values of u = a + B x with a general (non-symmetric) B: constant strain and rotation.
Eigen::VectorXd LinearField(const Eigen::Matrix3Xd& nodes) {
  Eigen::Matrix3d B;
  B << 1.0, -0.4, 0.7, 0.2, -0.8, 0.5, -0.6, 0.9, 0.3;
  const Eigen::Vector3d a(1e-3, -2e-3, 0.5e-3);
  const Eigen::Matrix3Xd u = (1e-3 * B * nodes).colwise() + a;
  return u.reshaped();
}

// Entries `dofs` of `x`.
Eigen::VectorXd Select(const Eigen::VectorXd& x, const std::vector<int>& dofs) {
  Eigen::VectorXd y(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k) y(static_cast<Eigen::Index>(k)) = x(dofs[k]);
  return y;
}

// Solves K_ff u_f = -K_fb u_b with u_b = u(fixed) and returns max |u_f - u(free)| / max |u|.
double InteriorError(const Eigen::SparseMatrix<double>& K, const std::vector<int>& free,
                     const std::vector<int>& fixed, const Eigen::VectorXd& u) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(testing::Submatrix(K, free, free));
  if (solver.info() != Eigen::Success) return INFINITY;
  const Eigen::VectorXd u_free =
      solver.solve(-(testing::Submatrix(K, free, fixed) * Select(u, fixed)));
  return (u_free - Select(u, free)).cwiseAbs().maxCoeff() / u.cwiseAbs().maxCoeff();
}

class PatchTest : public ::testing::TestWithParam<PatchCase> {
 protected:
  // A 3 x 3 x 3-cell distorted box, moved off the origin and rotated, and its assembled K.
  void SetUp() override {
    std::mt19937 rng(42 + static_cast<unsigned>(GetParam().type));
    box_ = testing::StructuredBox(GetParam().type, Eigen::Vector3i(3, 3, 3), kSize,
                                  GetParam().second_type, 1);
    testing::DistortInterior(&box_, kCornerFraction, GetParam().curved ? kCurveFraction : 0.0,
                             &rng);
    testing::Transform(&box_.mesh, testing::RandomRotation(&rng), Eigen::Vector3d(0.3, -1.2, 2.0));
    ASSERT_GT(testing::MinJacobian(box_.mesh), 0.0);
    K_ = AssembleSystem(box_.mesh, MassMatrixKind::kConsistent).stiffness;
    for (Eigen::Index v = 0; v < box_.mesh.num_nodes(); ++v) {
      auto& dofs = box_.on_boundary[static_cast<std::size_t>(v)] ? fixed_ : free_;
      for (int i = 0; i < 3; ++i) dofs.push_back(static_cast<int>(3 * v + i));
    }
    ASSERT_FALSE(free_.empty());
  }

  // max_i |(K x)_i| / (sum_j |K_ij x_j|) over the rows `rows`: K x relative to its round-off.
  double RelativeForce(const Eigen::VectorXd& x, const std::vector<int>& rows) const {
    const Eigen::VectorXd f = K_ * x;
    const Eigen::VectorXd scale = K_.cwiseAbs() * x.cwiseAbs();
    double worst = 0.0;
    for (int r : rows) {
      if (scale(r) > 0.0) worst = std::max(worst, std::abs(f(r)) / scale(r));
    }
    return worst;
  }

  testing::BoxMesh box_;
  Eigen::SparseMatrix<double> K_;
  std::vector<int> free_, fixed_;
};

TEST_P(PatchTest, InteriorSolutionReproducesLinearDisplacementField) {
  const double error = InteriorError(K_, free_, fixed_, LinearField(box_.mesh.nodes));
  std::printf("  %s: interior patch error %.2e (relative)\n", CaseName(GetParam()).c_str(), error);
  EXPECT_LT(error, kPatchTol);
}

TEST_P(PatchTest, LinearDisplacementFieldLeavesNoForceAtInteriorNodes) {
  EXPECT_LT(RelativeForce(LinearField(box_.mesh.nodes), free_), kForceTol);
}

TEST_P(PatchTest, RigidBodyFieldsLeaveNoForceAnywhere) {
  const Eigen::MatrixXd R = RigidBodyModes(box_.mesh.nodes);
  std::vector<int> all(static_cast<std::size_t>(K_.rows()));
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  for (int mode = 0; mode < 6; ++mode) {
    EXPECT_LT(RelativeForce(R.col(mode), all), kForceTol) << "rigid mode " << mode;
  }
}

TEST_P(PatchTest, StrainEnergyOfUniaxialStressAndSimpleShearIsAnalytic) {
  // Uniaxial stress sigma_xx = E eps: u = (eps x, -nu eps y, -nu eps z), energy E eps^2 V / 2.
  // Simple shear gamma (u_x = gamma y): energy G gamma^2 V / 2, G = E / (2 (1 + nu)).
  // From E and nu directly: checks the isotropic D (Lame constants) and the volume.
  const IsotropicMaterial& m = box_.mesh.blocks[0].material;
  const double volume = kSize.prod(), eps = 1e-3, gamma = 2e-3;
  const Eigen::Matrix3Xd& x = box_.mesh.nodes;
  Eigen::Matrix3Xd u_axial = Eigen::Matrix3Xd::Zero(3, x.cols()), u_shear = u_axial;
  u_axial.row(0) = eps * x.row(0);
  u_axial.row(1) = -m.poisson_ratio * eps * x.row(1);
  u_axial.row(2) = -m.poisson_ratio * eps * x.row(2);
  u_shear.row(0) = gamma * x.row(1);
  const Eigen::VectorXd a = u_axial.reshaped(), s = u_shear.reshaped();
  const double axial_exact = 0.5 * m.youngs_modulus_pa * eps * eps * volume;
  const double shear_exact =
      0.5 * m.youngs_modulus_pa / (2 * (1 + m.poisson_ratio)) * gamma * gamma * volume;
  EXPECT_NEAR(0.5 * a.dot(K_ * a), axial_exact, kEnergyTol * axial_exact);
  EXPECT_NEAR(0.5 * s.dot(K_ * s), shear_exact, kEnergyTol * shear_exact);
}

INSTANTIATE_TEST_SUITE_P(
    AllTypes, PatchTest,
    ::testing::Values(PatchCase{ElementType::kTet4, false}, PatchCase{ElementType::kTet10, false},
                      PatchCase{ElementType::kTet10, true}, PatchCase{ElementType::kHex8, false},
                      PatchCase{ElementType::kHex20, false}, PatchCase{ElementType::kHex20, true},
                      PatchCase{ElementType::kWedge6, false},
                      PatchCase{ElementType::kWedge15, false},
                      PatchCase{ElementType::kWedge15, true},
                      PatchCase{ElementType::kHex8, false, ElementType::kWedge6},
                      PatchCase{ElementType::kHex20, true, ElementType::kWedge15}),
    [](const auto& param_info) { return CaseName(param_info.param); });

TEST(PatchTest, GmshTet10CylinderWithCurvedSurfaceReproducesLinearField) {
  // A real curved mesh: gmsh puts the surface mid-side nodes on the cylinder.
  const double radius = 0.1, length = 0.3;
  const Mesh mesh = testing::GmshCylinder(radius, length, Eigen::Vector3d(0.1, 0.2, -0.1), 0.04);
  const Eigen::SparseMatrix<double> K = AssembleSystem(mesh, MassMatrixKind::kConsistent).stiffness;
  std::vector<int> free, fixed;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d p = mesh.nodes.col(v) - Eigen::Vector3d(0.1, 0.2, -0.1);
    const bool on_surface = std::abs(p.head<2>().norm() - radius) < 1e-6 * radius ||
                            std::abs(p(2)) < 1e-9 || std::abs(p(2) - length) < 1e-9;
    for (int i = 0; i < 3; ++i) (on_surface ? fixed : free).push_back(static_cast<int>(3 * v + i));
  }
  ASSERT_FALSE(free.empty());
  const double error = InteriorError(K, free, fixed, LinearField(mesh.nodes));
  std::printf("  gmsh tet10 cylinder (%ld elements): interior patch error %.2e (relative)\n",
              static_cast<long>(mesh.num_elements()), error);
  EXPECT_LT(error, kPatchTol);
}

// Collects element matrices into dense global K and M (M = m_e (x) I_3), the plain way.
class DenseAssembler final : public ElementMatrixVisitor {
 public:
  explicit DenseAssembler(Eigen::Index dofs) : K(Eigen::MatrixXd::Zero(dofs, dofs)), M(K) {}
  void Visit(std::span<const int> nodes, const Eigen::MatrixXd& K_e,
             const Eigen::MatrixXd& m_e) override {
    visited.emplace_back(nodes.begin(), nodes.end());
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      for (std::size_t b = 0; b < nodes.size(); ++b) {
        const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
        K.block<3, 3>(3 * nodes[a], 3 * nodes[b]) += K_e.block<3, 3>(3 * ia, 3 * ib);
        M.block<3, 3>(3 * nodes[a], 3 * nodes[b]).diagonal().array() += m_e(ia, ib);
      }
    }
  }
  Eigen::MatrixXd K, M;
  std::vector<std::vector<int>> visited;  ///< node lists of the visited elements, in order
};

// Round-off between two summation orders of the same element contributions.
constexpr double kAssemblyTol = 1e-14;

TEST(Assembly, SparseSystemEqualsDenseScatterOfElementMatricesOnMixedMesh) {
  std::mt19937 rng(5);
  testing::BoxMesh box =
      testing::StructuredBox(ElementType::kHex20, Eigen::Vector3i(3, 2, 2),
                             Eigen::Vector3d(0.6, 0.4, 0.4), ElementType::kWedge15, 2);
  testing::DistortInterior(&box, 0.2, 0.05, &rng);
  ASSERT_EQ(box.mesh.blocks.size(), 2u);
  for (MassMatrixKind kind : {MassMatrixKind::kConsistent, MassMatrixKind::kLumped}) {
    DenseAssembler dense(box.mesh.num_dofs());
    VisitElementMatrices(box.mesh, kind, 0, box.mesh.num_elements(), dense);
    const SystemMatrices system = AssembleSystem(box.mesh, kind);
    const Eigen::MatrixXd K(system.stiffness), M(system.mass);
    EXPECT_LT((K - dense.K).norm(), kAssemblyTol * dense.K.norm());
    EXPECT_LT((M - dense.M).norm(), kAssemblyTol * dense.M.norm());
    EXPECT_LT((K - K.transpose()).norm(), kAssemblyTol * K.norm());
    EXPECT_LT((M - M.transpose()).norm(), kAssemblyTol * M.norm());
  }
}

TEST(Assembly, VisitsExactlyTheRequestedElementRangeAcrossBlocks) {
  const testing::BoxMesh box =
      testing::StructuredBox(ElementType::kHex8, Eigen::Vector3i(3, 2, 1),
                             Eigen::Vector3d(0.6, 0.4, 0.2), ElementType::kWedge6, 1);
  ASSERT_EQ(box.mesh.blocks[0].num_elements(), 2);  // 2 hexes, then 8 wedges
  DenseAssembler dense(box.mesh.num_dofs());
  VisitElementMatrices(box.mesh, MassMatrixKind::kConsistent, 1, 5, dense);
  ASSERT_EQ(dense.visited.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const int global = 1 + k;
    const ElementBlock& block = box.mesh.blocks[global < 2 ? 0 : 1];
    const auto col = block.connectivity.col(global < 2 ? global : global - 2);
    EXPECT_EQ(dense.visited[static_cast<std::size_t>(k)], std::vector<int>(col.begin(), col.end()));
  }
}

TEST(Assembly, RejectsAnInvertedElementNamingIt) {
  testing::BoxMesh box = testing::StructuredBox(ElementType::kTet4, Eigen::Vector3i(2, 1, 1),
                                                Eigen::Vector3d(1, 1, 1));
  box.mesh.blocks[0].connectivity.col(5).segment<2>(1).reverseInPlace();  // swap nodes 1, 2
  try {
    AssembleSystem(box.mesh, MassMatrixKind::kConsistent);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tet4 element 6 "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-positive Jacobian"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace flexmbs::fem
