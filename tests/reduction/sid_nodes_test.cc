// Marker nodes of a reduced body: interface markers and the `sid:` section's markers.
#include "reduction/sid_nodes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "basis_test_support.h"
#include "core/error.h"
#include "core/skew.h"
#include "reduction/craig_bampton.h"
#include "reduction/sid_body_builder.h"
#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;

// Rigid motions of O(1) amplitude on a body of O(0.1) m: the rigid fit reproduces them up to
// the round-off of a 6 x 6 solve (measured 2.6e-14, the rotations psi; 2.1e-15 the
// translations; was 1e-12).
constexpr double kRigidRoundOff = 3e-13;
// Craig-Bampton constraint modes at an averaging interface: W u = q_b holds to the round-off of
// the dependent-DOF solve and the interior Cholesky solve (interface_coupling.h); measured
// 8.9e-16 (was 1e-10).
constexpr double kConstraintRoundOff = 1e-14;

Eigen::Vector3d Centroid(const fem::Mesh& mesh, const std::vector<int>& nodes) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int n : nodes) sum += mesh.nodes.col(n);
  return sum / static_cast<double>(nodes.size());
}

// The SID relations every node satisfies: origin m1 = phi columns, AP m0 = I, AP m1[j] = psi_j~,
// and no stiffening blocks.
void ExpectNodeRelations(const sid::Node& node, Eigen::Index n) {
  SCOPED_TRACE(node.name);
  ASSERT_EQ(node.phi.m0.rows(), 3);
  ASSERT_EQ(node.phi.m0.cols(), n);
  ASSERT_EQ(node.psi.m0.cols(), n);
  ASSERT_EQ(node.origin.m1.size(), static_cast<std::size_t>(n));
  ASSERT_EQ(node.AP.m1.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(node.AP.m0, Eigen::MatrixXd(Eigen::Matrix3d::Identity()));
  for (Eigen::Index j = 0; j < n; ++j) {
    EXPECT_EQ(node.origin.m1[static_cast<std::size_t>(j)], Eigen::MatrixXd(node.phi.m0.col(j)));
    EXPECT_EQ(node.AP.m1[static_cast<std::size_t>(j)], Eigen::MatrixXd(Skew(node.psi.m0.col(j))));
  }
  EXPECT_TRUE(node.phi.m1.empty());
  EXPECT_TRUE(node.psi.m1.empty());
  EXPECT_TRUE(node.origin.IsConsistent(n));
  EXPECT_TRUE(node.AP.IsConsistent(n));
}

TEST(MarkerNodes, RigidBodyModesMoveEveryMarkerWithTheRigidMotion) {
  testing::Body b =
      testing::MakeBox(ElementType::kTet10, {3, 1, 1}, {0.3, 0.06, 0.05}, testing::Steel());
  fem::Mesh& mesh = b.mesh;
  mesh.node_sets["root"] = testing::NodesAt(mesh, 0, 0.0);
  mesh.node_sets["end"] = testing::NodesAt(mesh, 0, 0.3);
  mesh.node_sets["mid"] = testing::NodesAt(mesh, 0, 0.1);
  mesh.node_sets["face"] = testing::NodesAt(mesh, 1, 0.0);
  mesh.node_sets["one"] = {mesh.node_sets["mid"][2]};

  // Two rigid motions u = t + theta x x and one arbitrary field.
  const std::vector<Eigen::Vector3d> t = {{0.3, -1.0, 0.5}, {0.0, 0.2, -0.7}};
  const std::vector<Eigen::Vector3d> theta = {{1.0, 0.4, -0.6}, {-0.2, 0.9, 0.3}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::MatrixXd Phi(mesh.num_dofs(), 3);
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    for (int k = 0; k < 2; ++k)
      Phi.block<3, 1>(3 * n, k) = t[k] + theta[k].cross(mesh.nodes.col(n));
    for (int a = 0; a < 3; ++a) Phi(3 * n + a, 2) = unit(rng);
  }

  BoundaryConditions held_by;
  held_by.interfaces.push_back(
      {"root", mesh.node_sets["root"], Coupling::kRigid, std::nullopt, {}});
  held_by.interfaces.push_back(
      {"face", mesh.node_sets["face"], Coupling::kNodes, std::nullopt, {}});
  std::vector<double> weights;
  for (std::size_t k = 0; k < mesh.node_sets["end"].size(); ++k)
    weights.push_back(1.0 + unit(rng) * unit(rng));
  const Eigen::Vector3d p_hub(0.35, 0.01, 0.02);
  held_by.interfaces.push_back(
      {"hub", mesh.node_sets["end"], Coupling::kAveraging, p_hub, weights});
  const Eigen::Vector3d p_tip(0.3, 0.03, 0.1);
  const std::vector<MarkerSetting> markers = {
      {"mid", "mid", MarkerCoupling::kAveraging, std::nullopt, std::nullopt},
      {"tip", "end", MarkerCoupling::kRigid, p_tip, std::nullopt},
      {"point", "one", MarkerCoupling::kNode, std::nullopt, std::nullopt},
  };

  const std::vector<sid::Node> nodes = MarkerNodes(mesh, Phi, held_by, markers);
  ASSERT_EQ(nodes.size(), 5u);  // the node-set interface "face" has no marker
  const std::vector<std::string> names = {"root", "hub", "mid", "tip", "point"};
  const std::vector<std::string> couplings = {"rigid", "averaging", "averaging", "rigid", "node"};
  const std::vector<Eigen::Vector3d> positions = {Centroid(mesh, mesh.node_sets["root"]), p_hub,
                                                  Centroid(mesh, mesh.node_sets["mid"]), p_tip,
                                                  mesh.nodes.col(mesh.node_sets["one"][0])};
  const std::vector<std::string> sets = {"root", "end", "mid", "end", "one"};
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const sid::Node& node = nodes[i];
    SCOPED_TRACE(names[i]);
    EXPECT_EQ(node.name, names[i]);
    EXPECT_EQ(node.coupling, couplings[i]);
    EXPECT_EQ(node.fe_nodes, mesh.node_sets[sets[i]]);
    ExpectNodeRelations(node, 3);
    EXPECT_LT((node.origin.m0 - positions[i]).norm(), kRigidRoundOff);
    for (int k = 0; k < 2; ++k) {
      EXPECT_LT((node.phi.m0.col(k) - (t[k] + theta[k].cross(positions[i]))).norm(), kRigidRoundOff)
          << "mode " << k;
      EXPECT_LT((node.psi.m0.col(k) - theta[k]).norm(), kRigidRoundOff) << "mode " << k;
    }
  }
  // The single node carries its own displacement for any field.
  EXPECT_EQ(Eigen::MatrixXd(nodes[4].phi.m0.col(2)),
            Eigen::MatrixXd(Phi.block<3, 1>(3 * mesh.node_sets["one"][0], 2)));
  // An averaging marker of an arbitrary field is the least-squares rigid fit: the residual
  // u_n - (t + theta x r_n) is orthogonal to every rigid motion, sum_n S(r_n)^T residual_n = 0.
  Eigen::Matrix<double, 6, 1> normal_equation = Eigen::Matrix<double, 6, 1>::Zero();
  for (const int n : mesh.node_sets["mid"]) {
    const Eigen::Vector3d r = mesh.nodes.col(n) - positions[2];
    const Eigen::Vector3d t_mid = nodes[2].phi.m0.col(2);
    const Eigen::Vector3d theta_mid = nodes[2].psi.m0.col(2);
    const Eigen::Vector3d residual = Phi.block<3, 1>(3 * n, 2) - t_mid - theta_mid.cross(r);
    normal_equation += RigidMotionMatrix(r).transpose() * residual;
  }
  EXPECT_LT(normal_equation.norm(), kRigidRoundOff);
}

TEST(MarkerNodes, CraigBamptonConstraintModesMoveTheirOwnInterfaceMarkerByOne) {
  testing::Body b =
      testing::MakeBox(ElementType::kHex8, {4, 1, 1}, {0.4, 0.05, 0.05}, testing::Steel());
  BoundaryConditions conditions;
  conditions.interfaces.push_back(
      {"root", testing::NodesAt(b.mesh, 0, 0.0), Coupling::kRigid, std::nullopt, {}});
  conditions.interfaces.push_back(
      {"tip", testing::NodesAt(b.mesh, 0, 0.4), Coupling::kAveraging, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 3;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  ASSERT_EQ(cb.num_modes(), 15);
  const std::vector<sid::Node> nodes = MarkerNodes(b.mesh, cb.Phi, cb.held_by, {});
  ASSERT_EQ(nodes.size(), 2u);
  // [phi; psi] of interface i: the identity on its own six constraint columns, zero elsewhere
  // (the other interface's constraint modes and the fixed-interface normal modes hold it).
  for (std::size_t i = 0; i < 2; ++i) {
    Eigen::MatrixXd motion(6, cb.num_modes());
    motion << nodes[i].phi.m0, nodes[i].psi.m0;
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, cb.num_modes());
    expected.middleCols<6>(6 * static_cast<Eigen::Index>(i)).setIdentity();
    EXPECT_LT((motion - expected).cwiseAbs().maxCoeff(), kConstraintRoundOff) << nodes[i].name;
    ExpectNodeRelations(nodes[i], cb.num_modes());
  }
}

// docs/sid.md, "Geometric stiffening": with sid.geometric_stiffening off, no stiffening matrices,
// Ct and the nodes' phi, psi of order 0, Cr and Oe still of order 1 (their kinematic parts);
// with it on, all of them of order 1.
TEST(MarkerNodes, WithoutGeometricStiffeningCtAndNodeBlocksAreOrderZero) {
  const testing::Body b = testing::MakeBox(ElementType::kHex8, {4, 1, 1}, {0.4, 0.05, 0.05}, testing::Steel());
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", testing::NodesAt(b.mesh, 0, 0.0)});
  conditions.interfaces.push_back({"tip", testing::NodesAt(b.mesh, 0, 0.4), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 3;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  for (const bool stiffening : {false, true}) {
    SCOPED_TRACE(stiffening ? "stiffening on" : "stiffening off");
    SidSpec sid;
    sid.geometric_stiffening = stiffening;
    const sid::ReducedBody body = BuildReducedBody(b.mesh, b.model(), fem::MassMatrixKind::kConsistent, sid, cb);
    const int order = stiffening ? 1 : 0;
    EXPECT_EQ(body.stiffening.empty(), !stiffening);
    EXPECT_EQ(body.Ct.order(), order);
    EXPECT_EQ(body.Cr.order(), 1);
    EXPECT_EQ(body.Oe.order(), 1);
    ASSERT_EQ(body.nodes.size(), 1u);
    EXPECT_EQ(body.nodes[0].phi.order(), order);
    EXPECT_EQ(body.nodes[0].psi.order(), order);
  }
}

// The built body holds its marker nodes and contact surfaces in the order of their names, the
// order its .sid.h5 file gives them back in: the interface marker 'tip' after a sid: marker 'mid',
// surfaces asked for as [top, bottom] as [bottom, top] (the ASCII SID numbered nodes in one order
// from `reduce --format sid-ascii` and in the other from `export` of the file).
TEST(MarkerNodes, NodesAndSurfacesAreInNameOrder) {
  testing::Body b = testing::MakeBox(ElementType::kHex8, {4, 1, 1}, {0.4, 0.05, 0.05}, testing::Steel());
  b.mesh.node_sets["mid"] = testing::NodesAt(b.mesh, 0, 0.2);
  b.mesh.node_sets["top"] = testing::NodesAt(b.mesh, 2, 0.05);
  b.mesh.node_sets["bottom"] = testing::NodesAt(b.mesh, 2, 0.0);
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", testing::NodesAt(b.mesh, 0, 0.0)});
  conditions.interfaces.push_back({"tip", testing::NodesAt(b.mesh, 0, 0.4), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 2;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  SidSpec sid;
  sid.markers.push_back({"mid", "mid", MarkerCoupling::kAveraging, std::nullopt, std::nullopt});
  sid.contact_surfaces = {"top", "bottom"};
  const sid::ReducedBody body = BuildReducedBody(b.mesh, b.model(), fem::MassMatrixKind::kConsistent, sid, cb);
  ASSERT_EQ(body.nodes.size(), 2u);
  EXPECT_EQ(body.nodes[0].name, "mid");
  EXPECT_EQ(body.nodes[1].name, "tip");
  ASSERT_EQ(body.surfaces.size(), 2u);
  EXPECT_EQ(body.surfaces[0].name, "bottom");
  EXPECT_EQ(body.surfaces[1].name, "top");
}

TEST(MarkerNodes, BadMarkersAreOneLineInputErrors) {
  testing::Body b =
      testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.05, 0.05}, testing::Steel());
  fem::Mesh& mesh = b.mesh;
  mesh.node_sets["end"] = testing::NodesAt(mesh, 0, 0.2);
  // The four nodes of the edge y = z = 0 lie on one line.
  mesh.node_sets["edge"] = testing::NodesWhere(
      mesh, [](const Eigen::Vector3d& x) { return x(1) == 0.0 && x(2) == 0.0; });
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::Ones(mesh.num_dofs(), 2);
  BoundaryConditions held_by;
  held_by.interfaces.push_back({"end", mesh.node_sets["end"], Coupling::kRigid, std::nullopt, {}});
  auto error_of = [&](const MarkerSetting& marker) {
    return flexmbs::testing::InputErrorMessage([&] { MarkerNodes(mesh, Phi, held_by, {marker}); });
  };
  EXPECT_EQ(
      error_of({"p", "end", MarkerCoupling::kNode, std::nullopt, std::nullopt}),
      "sid.markers 'p': coupling 'node' needs a node set of exactly one FE node; 'end' has 4");
  EXPECT_EQ(error_of({"p", "hole", MarkerCoupling::kRigid, std::nullopt, std::nullopt}),
            "sid.markers 'p': the mesh has no node set 'hole'");
  EXPECT_EQ(error_of({"end", "end", MarkerCoupling::kRigid, std::nullopt, std::nullopt}),
            "sid.markers 'end': the name 'end' is already a marker or interface marker");
  EXPECT_EQ(error_of({"line", "edge", MarkerCoupling::kAveraging, std::nullopt, std::nullopt}),
            "sid.markers 'line': interface 'line': averaging coupling needs nodes that are not all "
            "on one line: the "
            "marker's rotation about the line is undetermined (3 nodes)");
}

TEST(InterfaceMarkerNames, AreTheNodeSetsOfRigidAndAveragingInterfaces) {
  ReductionSpec spec;
  spec.interfaces = {{"a", Coupling::kNodes, std::nullopt},
                     {"b", Coupling::kRigid, std::nullopt},
                     {"c", Coupling::kAveraging, std::nullopt}};
  EXPECT_EQ(InterfaceMarkerNames(spec), (std::vector<std::string>{"b", "c"}));
}

}  // namespace
}  // namespace flexmbs::reduction
