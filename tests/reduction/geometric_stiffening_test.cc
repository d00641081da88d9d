// Geometric (stress) stiffening: the linear elastic stress, the assembled and the
// element-by-element projected K_G against each other, buckling of a column
// against Euler, and the SID stiffening load cases against the body's mass properties.
#include "reduction/geometric_stiffening.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "basis_test_support.h"
#include "core/error.h"
#include "fem/element_integrator.h"
#include "fem/geometric_stiffness.h"
#include "fem/mass_properties.h"
#include "fem/reference_element.h"
#include "reduction/dof_constraints.h"
#include "reduction/interior_problem.h"
#include "reduction/modal_basis.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs {
namespace {

using fem::ElementType;
using Index = Eigen::Index;

// Quadrature against exact integrals of the same polynomial, or two orders of one sum: a few
// hundred roundings of O(1) terms.
constexpr double kRoundOff = 1e-12;

const fem::IsotropicMaterial kSteel{"steel", 2.1e11, 0.3, 7850.0};

TEST(LinearElasticStress, UniaxialStrainStateGivesUniaxialStress) {
  // eps = diag(e, -nu e, -nu e) is the strain of the uniaxial stress sigma_xx = E e.
  const double e = 1e-4, nu = kSteel.poisson_ratio;
  Eigen::Matrix3d grad_u = Eigen::Vector3d(e, -nu * e, -nu * e).asDiagonal();
  grad_u(0, 1) = 3e-5;  // plus a rigid rotation about z: no stress
  grad_u(1, 0) = -3e-5;
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  expected(0, 0) = kSteel.youngs_modulus_pa * e;
  EXPECT_LE((fem::LinearElasticStress(grad_u, kSteel) - expected).cwiseAbs().maxCoeff(), kRoundOff * expected(0, 0));
}

TEST(GeometricStiffness, ElementByElementProjectionEqualsTheProjectedAssembledMatrix) {
  // A mixed hex20 / wedge15 box, distorted and curved (the two agree whatever the quadrature).
  fem::testing::BoxMesh box = fem::testing::StructuredBox(ElementType::kHex20, {3, 2, 2}, {0.3, 0.1, 0.1},
                                                          ElementType::kWedge15, 2);
  std::mt19937 rng(3);
  fem::testing::DistortInterior(&box, 0.15, 0.05, &rng);
  fem::Mesh& mesh = box.mesh;
  for (fem::ElementBlock& block : mesh.blocks) block.material = kSteel;
  const Index dofs = mesh.num_dofs();
  const Eigen::MatrixXd U = 1e-4 * Eigen::MatrixXd::Random(dofs, 3);
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::Random(dofs, 5);
  const std::vector<Eigen::MatrixXd> projected = fem::ProjectedGeometricStiffness(mesh, U, Phi);
  ASSERT_EQ(projected.size(), 3u);
  const Eigen::SparseMatrix<double> pattern = fem::SystemPattern(mesh);
  for (Index c = 0; c < 3; ++c) {
    const Eigen::SparseMatrix<double> K_G = fem::AssembleGeometricStiffness(mesh, U.col(c));
    EXPECT_EQ(K_G.nonZeros(), pattern.nonZeros());
    const Eigen::SparseMatrix<double> K_G_T = K_G.transpose();
    EXPECT_LE((K_G - K_G_T).norm(), kRoundOff * K_G.norm());
    const Eigen::MatrixXd expected = Phi.transpose() * (K_G * Phi);
    const Eigen::MatrixXd& got = projected[static_cast<std::size_t>(c)];
    EXPECT_LE((got - expected).norm(), kRoundOff * expected.norm()) << "field " << c;
    EXPECT_LE((got - got.transpose()).norm(), kRoundOff * expected.norm());
  }
}

TEST(GeometricStiffness, AssembledAndElementByElementStiffeningMatricesAgree) {
  // The distorted mixed box again; the second field is zero (a load carried by the hold).
  fem::testing::BoxMesh box = fem::testing::StructuredBox(ElementType::kHex20, {3, 2, 2}, {0.3, 0.1, 0.1},
                                                          ElementType::kWedge15, 2);
  std::mt19937 rng(5);
  fem::testing::DistortInterior(&box, 0.15, 0.05, &rng);
  fem::Mesh& mesh = box.mesh;
  for (fem::ElementBlock& block : mesh.blocks) block.material = kSteel;
  Eigen::MatrixXd U = 1e-4 * Eigen::MatrixXd::Random(mesh.num_dofs(), 3);
  U.col(1).setZero();
  using reduction::StiffeningProjection;
  Index first_assembled = 1;  // the fewest modes for which kAuto assembles 3 cases
  while (!reduction::AssembledProjectionIsFaster(first_assembled, 3)) ++first_assembled;
  for (const Index n : {first_assembled - 1, first_assembled}) {
    const Eigen::MatrixXd Phi = Eigen::MatrixXd::Random(mesh.num_dofs(), n);
    const auto element = reduction::ProjectedStiffeningMatrices(mesh, U, Phi, StiffeningProjection::kElementByElement);
    const auto assembled = reduction::ProjectedStiffeningMatrices(mesh, U, Phi, StiffeningProjection::kAssembled);
    const auto automatic = reduction::ProjectedStiffeningMatrices(mesh, U, Phi);
    ASSERT_EQ(assembled.size(), 3u);
    for (std::size_t c = 0; c < 3; ++c) {
      const double scale = element[0].norm();
      EXPECT_LE((assembled[c] - element[c]).norm(), kRoundOff * scale) << "n " << n << ", field " << c;
      EXPECT_EQ(assembled[c], assembled[c].transpose());
      // kAuto picks one of the two: the same numbers bit for bit.
      EXPECT_EQ(automatic[c], n < first_assembled ? element[c] : assembled[c]);
    }
    EXPECT_TRUE(assembled[1].isZero(0.0));
  }
}

// ---- Buckling of a cantilever column -----------------------------------------------------

constexpr double kColumnLength = 1.0, kColumnSide = 0.02;
// The hex20 column of 16 x 2 x 2 cells, its root face sliding (u_x = 0, the section free to
// contract): the Euler load pi^2 E I / (4 L^2) of the clamped-free column within the
// discretisation error (measured +1.5e-2, +3.1e-3, +3.4e-4 on 4, 8, 16 cells: ~h^3) plus the
// shear flexibility of the 3-D body (P_E / (k G A) = 2.6e-4 lower, Timoshenko).
constexpr double kEulerTolerance = 1e-3;
// With the root face fully clamped, the clamp's restraint of the Poisson contraction makes
// singular edges (Williams 1952) that converge slowly: measured +1.36e-2, +5.5e-3, +2.5e-3 on
// 8, 16, 32 cells (~h^1.4), towards +1e-3 or less.
constexpr double kClampedEulerTolerance = 1e-2;
// Rayleigh-Ritz on the ten lowest fixed-interface vibration modes (five per bending plane):
// the buckling shape is not a vibration mode; measured +5.4e-4 above the full model's P_cr.
constexpr double kRitzTolerance = 2e-3;
// The dense generalized eigensolver's relative error in P_cr: eps cond(K), cond(K) ~ 1e8.
constexpr double kDenseBucklingRoundOff = 1e-7;

double EulerLoad() {
  const double I = std::pow(kColumnSide, 4) / 12.0;
  return std::pow(std::numbers::pi, 2) * kSteel.youngs_modulus_pa * I / (4.0 * kColumnLength * kColumnLength);
}

testing::Body Column() {
  return testing::MakeBox(ElementType::kHex20, {16, 2, 2}, {kColumnLength, kColumnSide, kColumnSide},
                                     kSteel);
}

// The smallest P > 0 with (K - P K_G1) x = 0 on the DOF selected by `free`: the buckling load
// of a column whose unit tension has the geometric stiffness K_G1 (dense; K_G1 x = (1/P) K x).
double LowestBucklingLoad(const Eigen::MatrixXd& K, const Eigen::MatrixXd& K_G1) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K_G1, K, Eigen::EigenvaluesOnly);
  return 1.0 / solver.eigenvalues().maxCoeff();
}

TEST(ColumnBuckling, UniaxialPrestressGivesTheEulerLoad) {
  // The exact field of a unit axial tension, u = (x, -nu y, -nu z) / (E A), gives the uniform
  // stress sigma_xx = 1 / A through the element stress; K with it buckles at P_E.
  const testing::Body b = Column();
  const double strain = 1.0 / (kSteel.youngs_modulus_pa * kColumnSide * kColumnSide);
  Eigen::VectorXd u(b.mesh.num_dofs());
  for (Index n = 0; n < b.mesh.num_nodes(); ++n) {
    const Eigen::Vector3d x = b.mesh.nodes.col(n);
    u.segment<3>(3 * n) = strain * Eigen::Vector3d(x(0), -kSteel.poisson_ratio * x(1), -kSteel.poisson_ratio * x(2));
  }
  const Eigen::SparseMatrix<double> K_G = fem::AssembleGeometricStiffness(b.mesh, u);
  // The root face slides: u_x = 0 on it, u_y = 0 on its line y = h/2 and u_z = 0 on z = h/2
  // (the symmetry lines of the section, which stay put when it contracts).
  std::vector<Index> fixed;
  for (const int n : testing::NodesAt(b.mesh, 0, 0.0)) {
    fixed.push_back(3 * n);
    for (int axis : {1, 2}) {
      if (std::abs(b.mesh.nodes(axis, n) - 0.5 * kColumnSide) < 1e-12) fixed.push_back(3 * n + axis);
    }
  }
  const reduction::FreeDofMap free(b.mesh.num_dofs(), fixed);
  const double P = LowestBucklingLoad(Eigen::MatrixXd(free.Restrict(b.K)), Eigen::MatrixXd(free.Restrict(K_G)));
  std::printf("[ numbers  ] column, uniaxial prestress: P_cr %.6g N, Euler %.6g N, error %+.2e\n", P, EulerLoad(),
              P / EulerLoad() - 1.0);
  EXPECT_NEAR(P / EulerLoad(), 1.0, kEulerTolerance);
}

TEST(ColumnBuckling, TipForceStiffeningOfAReducedColumnGivesTheEulerLoad) {
  // A marker at the tip face (averaging), the column clamped at x = 0 and reduced to its lowest
  // fixed-interface modes: K0F_x is the stiffening of a unit tension at the marker, so the
  // reduced column buckles where Ke - P K0F_x turns singular. Rayleigh-Ritz on a subspace: P is
  // an upper bound of the full model's P_cr with the same prestress (the static response to
  // the same nodal load).
  const testing::Body b = Column();
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0);
  reduction::BoundaryConditions clamp;
  clamp.supports.push_back({"root", root});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 10;
  const reduction::ReducedBasis basis =
      reduction::FixedInterfaceModalBasis(b.model(), clamp, eigen, testing::Spectra());
  const reduction::InterfaceSpec tip{"tip", testing::NodesAt(b.mesh, 0, kColumnLength),
                                     reduction::Coupling::kAveraging, std::nullopt, {}};
  const reduction::StiffeningResult s =
      reduction::ComputeGeometricStiffening(b.mesh, b.model(), clamp, basis.Phi, std::span(&tip, 1));
  ASSERT_EQ(s.nodes.size(), 1u);
  const double P_reduced = LowestBucklingLoad(basis.K_reduced, s.nodes[0].K0F[0]);

  const Eigen::MatrixXd F = reduction::BuildStiffeningLoads(b.model(), std::span(&tip, 1));
  const auto free = reduction::FreeDofMap::ClampNodes(b.mesh.num_nodes(), root);
  const Eigen::MatrixXd K_ff = Eigen::MatrixXd(free.Restrict(b.K));
  const Eigen::VectorXd x = free.Expand(Eigen::MatrixXd(K_ff.llt().solve(free.RestrictVectors(F.col(12)))));
  const double P_full =
      LowestBucklingLoad(K_ff, Eigen::MatrixXd(free.Restrict(fem::AssembleGeometricStiffness(b.mesh, x))));
  std::printf("[ numbers  ] column, tip force, clamped: reduced P_cr %.6g N (%+.2e to full), full %.6g N (%+.2e to "
              "Euler %.6g N)\n",
              P_reduced, P_reduced / P_full - 1.0, P_full, P_full / EulerLoad() - 1.0, EulerLoad());
  EXPECT_NEAR(P_full / EulerLoad(), 1.0, kClampedEulerTolerance);
  EXPECT_GE(P_reduced / P_full - 1.0, -kDenseBucklingRoundOff);  // an upper bound
  EXPECT_LE(P_reduced / P_full - 1.0, kRitzTolerance);
}

// ---- The stiffening load cases -----------------------------------------------------------

TEST(StiffeningLoads, BodyForceLoadsHaveTheResultantsOfTheMassProperties) {
  // Resultant force and moment about Bo of each body-force case against the mass properties
  // integrated from the geometry (not from M): -m e_a and -m c x e_a; for -rho e_a x r the
  // force -e_a x m c and moment -J_Bo e_a; for -rho W_l r the force -W_l m c and moment
  // -int r x W_l r dm.
  fem::Mesh mesh = fem::testing::StructuredBox(ElementType::kTet10, {3, 2, 2}, {0.3, 0.1, 0.2}).mesh;
  fem::testing::Transform(&mesh, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.2, -0.1, 0.05));
  const testing::Body b = testing::AssembleBody(mesh);
  const fem::MassProperties props = fem::IntegrateMassProperties(b.mesh);
  const double m = props.mass_kg;
  const Eigen::Vector3d mc = m * props.p_BoCm_B;
  // Second moment int r r^T dm about Bo.
  const Eigen::Matrix3d J_cm = props.I_Cm_B;
  const Eigen::Matrix3d S = (0.5 * J_cm.trace() * Eigen::Matrix3d::Identity() - J_cm) +
                            m * props.p_BoCm_B * props.p_BoCm_B.transpose();
  const Eigen::Matrix3d J_o = S.trace() * Eigen::Matrix3d::Identity() - S;

  const reduction::InterfaceSpec marker{"m", testing::NodesAt(b.mesh, 0, 0.5),
                                        reduction::Coupling::kRigid, Eigen::Vector3d(0.6, 0.0, 0.1), {}};
  const Eigen::MatrixXd F = reduction::BuildStiffeningLoads(b.model(), std::span(&marker, 1));
  ASSERT_EQ(F.cols(), 18);
  auto resultant = [&](Index c, const Eigen::Vector3d& about) {
    Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
    for (Index n = 0; n < b.mesh.num_nodes(); ++n) {
      const Eigen::Vector3d f = F.block<3, 1>(3 * n, c);
      r.head<3>() += f;
      r.tail<3>() += (b.mesh.nodes.col(n) - about).cross(f);
    }
    return r;
  };
  const double force_scale = m, moment_scale = J_o.norm();
  auto expect = [&](Index c, const Eigen::Vector3d& force, const Eigen::Vector3d& moment, const Eigen::Vector3d& about) {
    const Eigen::Matrix<double, 6, 1> r = resultant(c, about);
    EXPECT_LE((r.head<3>() - force).norm(), kRoundOff * force_scale) << "case " << c;
    EXPECT_LE((r.tail<3>() - moment).norm(), kRoundOff * moment_scale) << "case " << c;
  };
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(a);
    expect(a, -m * e, -mc.cross(e), origin);
    expect(3 + a, -e.cross(mc), -J_o * e, origin);
  }
  for (int l = 0; l < 6; ++l) {
    // W_l from its definition d(w~ w~)/d omega_q,l, by differences of w~ w~ (exact: quadratic).
    auto ww = [](const Eigen::Vector3d& w) { return Eigen::Matrix3d(w * w.transpose() - w.squaredNorm() * Eigen::Matrix3d::Identity()); };
    const int pairs[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    Eigen::Matrix3d W;
    if (l < 3) {
      W = ww(Eigen::Vector3d::Unit(l));
    } else {
      const auto [i, j] = pairs[l - 3];
      W = ww(Eigen::Vector3d::Unit(i) + Eigen::Vector3d::Unit(j)) - ww(Eigen::Vector3d::Unit(i)) -
          ww(Eigen::Vector3d::Unit(j));
    }
    // int r x (W r) dm = sum over the skew of W S (S symmetric): component k = eps_kij (W S)_ji.
    const Eigen::Matrix3d WS = W * S;
    const Eigen::Vector3d moment(WS(2, 1) - WS(1, 2), WS(0, 2) - WS(2, 0), WS(1, 0) - WS(0, 1));
    expect(6 + l, -W * mc, -moment, origin);
  }
  const Eigen::Vector3d p_marker = *marker.marker_position;
  for (int a = 0; a < 3; ++a) {
    expect(12 + a, Eigen::Vector3d::Unit(a), Eigen::Vector3d::Zero(), p_marker);
    expect(15 + a, Eigen::Vector3d::Zero(), Eigen::Vector3d::Unit(a), p_marker);
  }
}

TEST(GeometricStiffening, LoadsCarriedByTheHoldOrBalancedByInertiaReliefCauseNoStiffening) {
  const testing::Body b = Column();
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0);
  const std::vector<int> tip_nodes = testing::NodesAt(b.mesh, 0, kColumnLength);
  const reduction::InterfaceSpec tip{"tip", tip_nodes, reduction::Coupling::kRigid, std::nullopt, {}};
  const reduction::InterfaceSpec corner{"corner", {tip_nodes.front()}, reduction::Coupling::kNodes, std::nullopt, {}};
  const reduction::InterfaceSpec nodes[] = {tip, corner};
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 4;

  // Held at the root (support) and the tip (interface): the tip's loads go into the hold.
  reduction::BoundaryConditions held;
  held.supports.push_back({"root", root});
  held.interfaces.push_back(tip);
  const reduction::ReducedBasis fixed =
      reduction::FixedInterfaceModalBasis(b.model(), held, eigen, testing::Spectra());
  const reduction::StiffeningResult s = reduction::ComputeGeometricStiffening(b.mesh, b.model(), held, fixed.Phi, nodes);
  const double scale = s.body.K0omega[1].norm();  // centrifugal load of spin about y: bends nothing, stretches
  ASSERT_GT(scale, 0.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(s.nodes[0].K0F[static_cast<std::size_t>(a)].norm(), 0.0);
    EXPECT_EQ(s.nodes[0].K0M[static_cast<std::size_t>(a)].norm(), 0.0);
    EXPECT_EQ(s.nodes[1].K0F[static_cast<std::size_t>(a)].norm(), 0.0);
    EXPECT_EQ(s.nodes[1].K0M[static_cast<std::size_t>(a)].size(), 0);  // a single FE node takes no moment
    EXPECT_GT(s.body.K0t[static_cast<std::size_t>(a)].norm(), 0.0);
  }

  // Free-free: a uniform acceleration is balanced by inertia entirely (no stress); a tip force
  // and a spin are not.
  reduction::FreeFreeOptions options;
  options.eigen.num_modes = 4;
  const reduction::ReducedBasis free =
      reduction::FreeFreeModalBasis(b.model(), options, testing::Spectra());
  const reduction::StiffeningResult f =
      reduction::ComputeGeometricStiffening(b.mesh, b.model(), {}, free.Phi, std::span(&tip, 1));
  const double free_scale = f.body.K0omega[1].norm();
  ASSERT_GT(free_scale, 0.0);
  // A uniform acceleration of the mass m equals the load; the relief cancels it to round-off
  // times cond(K) (~1e8 for this column).
  constexpr double kInertiaReliefResidual = 1e-7;
  for (int a = 0; a < 3; ++a) {
    const double relative = f.body.K0t[static_cast<std::size_t>(a)].norm() / free_scale;
    std::printf("[ numbers  ] free column: |K0t_%d| / |K0omega_2| = %.1e\n", a, relative);
    EXPECT_LE(relative, kInertiaReliefResidual) << "axis " << a;
  }
  EXPECT_GT(f.nodes[0].K0F[0].norm(), 0.0);
}

TEST(GeometricStiffening, ReusesTheBasisFactorisationOfTheHeldBodyWithTheSameResult) {
  // The same factor either way (CHOLMOD is deterministic): the same matrices up to round-off
  // (measured: 0).
  constexpr double kSameComputation = 1e-13;
  const testing::Body b = Column();
  reduction::BoundaryConditions held;
  held.supports.push_back({"root", testing::NodesAt(b.mesh, 0, 0.0)});
  const reduction::InterfaceSpec tip{"tip", testing::NodesAt(b.mesh, 0, kColumnLength),
                                     reduction::Coupling::kAveraging, std::nullopt, {}};
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 4;
  const reduction::ReducedBasis basis =
      reduction::FixedInterfaceModalBasis(b.model(), held, eigen, testing::Spectra());
  ASSERT_NE(basis.held_factorization, nullptr);
  reduction::StiffeningResult shared, own;
  EXPECT_EQ(testing::FactorizationsDuring([&] {
              shared = reduction::ComputeGeometricStiffening(b.mesh, b.model(), held, basis.Phi, std::span(&tip, 1),
                                                             basis.held_factorization.get());
            }),
            0);
  EXPECT_EQ(testing::FactorizationsDuring([&] {
              own = reduction::ComputeGeometricStiffening(b.mesh, b.model(), held, basis.Phi, std::span(&tip, 1));
            }),
            1);
  const auto expect_same = [&](const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
    EXPECT_LE((a - reference).cwiseAbs().maxCoeff(), kSameComputation * reference.cwiseAbs().maxCoeff());
  };
  for (std::size_t a = 0; a < 3; ++a) {
    expect_same(shared.body.K0t[a], own.body.K0t[a]);
    expect_same(shared.body.K0r[a], own.body.K0r[a]);
    expect_same(shared.nodes[0].K0F[a], own.nodes[0].K0F[a]);
    expect_same(shared.nodes[0].K0M[a], own.nodes[0].K0M[a]);
  }
  for (std::size_t l = 0; l < 6; ++l) expect_same(shared.body.K0omega[l], own.body.K0omega[l]);
  // A factor of other conditions is refused.
  reduction::BoundaryConditions other = held;
  other.supports[0].name = "base";
  EXPECT_THROW(reduction::ComputeGeometricStiffening(b.mesh, b.model(), other, basis.Phi, {},
                                                     basis.held_factorization.get()),
               InternalError);
}

TEST(GeometricStiffening, RejectsBadNodesAndSizes) {
  const testing::Body b = Column();
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(b.mesh.num_dofs(), 2);
  const reduction::InterfaceSpec two{"pad", {1, 2}, reduction::Coupling::kNodes, std::nullopt, {}};
  testing::ExpectInputError(
      [&] { reduction::ComputeGeometricStiffening(b.mesh, b.model(), {}, Phi, std::span(&two, 1)); },
      {"node 'pad': a node-set node must have exactly one FE node, not 2"});
  const reduction::InterfaceSpec outside{"pad", {1, 999999}, reduction::Coupling::kAveraging, std::nullopt, {}};
  testing::ExpectInputError(
      [&] { reduction::ComputeGeometricStiffening(b.mesh, b.model(), {}, Phi, std::span(&outside, 1)); },
      {"node 'pad': FE node 999999 is outside the mesh's node range"});
  testing::ExpectInputError(
      [&] { reduction::ComputeGeometricStiffening(b.mesh, b.model(), {}, Eigen::MatrixXd::Zero(6, 2)); },
      {"geometric stiffening: the basis has 6 rows"});
}

}  // namespace
}  // namespace flexmbs
