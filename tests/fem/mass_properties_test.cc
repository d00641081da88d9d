// Mass properties: from the consistent mass matrix (rigid-body projection) and by direct volume
// quadrature, against the analytic values of a box and a cylinder; HRZ lumped mass.

#include "fem/mass_properties.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "fem/assembly.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// Both computations are exact for affine/parallelepiped elements (the mass rule integrates
// rho x x^T det J exactly): what is left is round-off, amplified ~100x by the parallel-axis
// shift from the origin to the centre of mass (|c|^2 / radius of gyration^2 ~ 50 here).
constexpr double kExactTol = 1e-12;
// The same quadrature sum computed two ways (R^T M R vs sum_q w_q rho x_q x_q^T): round-off.
constexpr double kSameQuadratureTol = 1e-12;
// Discretisation error of a tet10 cylinder of radius 0.1 m at mesh size 0.04 m: quadratic
// geometry approximates the circle to O(h^3) per edge; measured ~3e-5, asserted loosely.
constexpr double kCylinderTol = 1e-3;

// Relative difference |a - b| / |b| of two mass-property sets, the worst of mass, centre of
// mass and inertia tensor (Frobenius norms).
struct Difference {
  double mass, centre, inertia;
  double Worst() const { return std::max({mass, centre, inertia}); }
};
Difference Compare(const MassProperties& a, const MassProperties& b) {
  return {std::abs(a.mass_kg - b.mass_kg) / b.mass_kg,
          (a.p_BoCm_B - b.p_BoCm_B).norm() / b.p_BoCm_B.norm(),
          (a.I_Cm_B - b.I_Cm_B).norm() / b.I_Cm_B.norm()};
}

// Analytic properties of a homogeneous box [0, size] mapped by x -> R x + t.
MassProperties BoxProperties(double density, const Eigen::Vector3d& size, const Eigen::Matrix3d& R,
                             const Eigen::Vector3d& t) {
  MassProperties p;
  p.mass_kg = density * size.prod();
  p.p_BoCm_B = R * (0.5 * size) + t;
  const Eigen::Vector3d s2 = size.cwiseAbs2();
  const Eigen::Vector3d principal =
      p.mass_kg / 12.0 * Eigen::Vector3d(s2(1) + s2(2), s2(0) + s2(2), s2(0) + s2(1));
  p.I_Cm_B = R * principal.asDiagonal() * R.transpose();
  return p;
}

struct BoxCase {
  ElementType type;
  bool rotated;    ///< rotate the box so that its inertia tensor has off-diagonal terms
  bool distorted;  ///< move interior corner nodes (straight edges: tetrahedra stay affine)
};

// The case's test name suffix, e.g. "tet10RotatedDistorted"; also how gtest prints it.
std::string CaseName(const BoxCase& c) {
  return std::string(Traits(c.type).name) + (c.rotated ? "Rotated" : "") +
         (c.distorted ? "Distorted" : "");
}
void PrintTo(const BoxCase& c, std::ostream* os) { *os << CaseName(c); }

class BoxMassTest : public ::testing::TestWithParam<BoxCase> {
 protected:
  // A 3 x 2 x 2-cell box 0.5 x 0.3 x 0.4 m, translated (and maybe rotated) off the origin.
  void SetUp() override {
    std::mt19937 rng(7);
    const Eigen::Vector3d size(0.5, 0.3, 0.4);
    box_ = testing::StructuredBox(GetParam().type, Eigen::Vector3i(3, 2, 2), size);
    if (GetParam().distorted) testing::DistortInterior(&box_, 0.2, 0.0, &rng);
    const Eigen::Matrix3d R =
        GetParam().rotated ? testing::RandomRotation(&rng) : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d t(0.8, -0.5, 0.6);
    testing::Transform(&box_.mesh, R, t);
    exact_ = BoxProperties(box_.mesh.blocks[0].material.density_kg_m3, size, R, t);
  }
  testing::BoxMesh box_;
  MassProperties exact_;
};

TEST_P(BoxMassTest, ConsistentMassMatrixGivesAnalyticMassCentreAndInertia) {
  const SystemMatrices system = AssembleSystem(box_.mesh, MassMatrixKind::kConsistent);
  const Difference d = Compare(MassPropertiesFromMassMatrix(system.mass, box_.mesh.nodes), exact_);
  EXPECT_LT(d.mass, kExactTol);
  EXPECT_LT(d.centre, kExactTol);
  EXPECT_LT(d.inertia, kExactTol);
}

TEST_P(BoxMassTest, VolumeIntegralsGiveAnalyticMassCentreAndInertia) {
  const Difference d = Compare(IntegrateMassProperties(box_.mesh), exact_);
  EXPECT_LT(d.mass, kExactTol);
  EXPECT_LT(d.centre, kExactTol);
  EXPECT_LT(d.inertia, kExactTol);
}

INSTANTIATE_TEST_SUITE_P(Boxes, BoxMassTest,
                         ::testing::Values(BoxCase{ElementType::kTet4, true, true},
                                           BoxCase{ElementType::kTet10, false, false},
                                           BoxCase{ElementType::kTet10, true, true},
                                           BoxCase{ElementType::kHex8, false, false},
                                           BoxCase{ElementType::kHex8, true, false},
                                           BoxCase{ElementType::kHex20, true, false},
                                           BoxCase{ElementType::kWedge6, true, false},
                                           BoxCase{ElementType::kWedge15, true, false}),
                         [](const auto& param_info) { return CaseName(param_info.param); });

TEST(LumpedMass, HrzKeepsMassAndCentreOfMassExactlyWithPositiveDiagonalForTet10) {
  // HRZ scales each element's diagonal to the element mass; on a straight-sided tet10 the
  // corner and mid-side diagonal entries are each equal, so the element centroid is kept too.
  std::mt19937 rng(11);
  const Eigen::Vector3d size(0.5, 0.3, 0.4);
  testing::BoxMesh box =
      testing::StructuredBox(ElementType::kTet10, Eigen::Vector3i(3, 2, 2), size);
  testing::DistortInterior(&box, 0.2, 0.0, &rng);
  const Eigen::Matrix3d R = testing::RandomRotation(&rng);
  const Eigen::Vector3d t(0.8, -0.5, 0.6);
  testing::Transform(&box.mesh, R, t);
  const MassProperties exact = BoxProperties(box.mesh.blocks[0].material.density_kg_m3, size, R, t);

  const Eigen::SparseMatrix<double> M = AssembleSystem(box.mesh, MassMatrixKind::kLumped).mass;
  EXPECT_EQ(M.nonZeros(), M.rows()) << "lumped mass must be diagonal";
  EXPECT_GT(Eigen::VectorXd(M.diagonal()).minCoeff(), 0.0);
  const Difference d = Compare(MassPropertiesFromMassMatrix(M, box.mesh.nodes), exact);
  EXPECT_LT(d.mass, kExactTol);
  EXPECT_LT(d.centre, kExactTol);
}

TEST(CylinderMass, ConsistentMassEqualsVolumeIntegralsAndApproachesAnalyticValues) {
  const double radius = 0.1, length = 0.5;
  const Eigen::Vector3d base(0.2, -0.1, 0.3);
  const Mesh mesh = testing::GmshCylinder(radius, length, base, 0.04);
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, ElementType::kTet10);

  MassProperties exact;
  exact.mass_kg = testing::Steel().density_kg_m3 * std::numbers::pi * radius * radius * length;
  exact.p_BoCm_B = base + Eigen::Vector3d(0, 0, 0.5 * length);
  const double transverse = exact.mass_kg * (3 * radius * radius + length * length) / 12.0;
  exact.I_Cm_B.diagonal() << transverse, transverse, 0.5 * exact.mass_kg * radius * radius;

  const SystemMatrices system = AssembleSystem(mesh, MassMatrixKind::kConsistent);
  const MassProperties from_matrix = MassPropertiesFromMassMatrix(system.mass, mesh.nodes);
  const MassProperties integrated = IntegrateMassProperties(mesh);
  EXPECT_LT(Compare(from_matrix, integrated).Worst(), kSameQuadratureTol);

  const Difference d = Compare(integrated, exact);
  std::printf(
      "  cylinder: %ld tet10, relative error vs analytic: mass %.2e, centre %.2e, "
      "inertia %.2e\n",
      static_cast<long>(mesh.num_elements()), d.mass, d.centre, d.inertia);
  EXPECT_LT(d.Worst(), kCylinderTol);

  // HRZ on curved elements still keeps the total mass exactly, with positive entries.
  const Eigen::SparseMatrix<double> lumped = AssembleSystem(mesh, MassMatrixKind::kLumped).mass;
  EXPECT_GT(Eigen::VectorXd(lumped.diagonal()).minCoeff(), 0.0);
  EXPECT_NEAR(lumped.sum() / 3.0, integrated.mass_kg, kSameQuadratureTol * integrated.mass_kg);
}

}  // namespace
}  // namespace flexmbs::fem
