// Supports by component (as Nastran SPCs on components 1-3 pose them): a steel beam clamped at
// its root and held in z only along its tip's bottom edge line, against a dense eigen-solve of
// K and M with those rows and columns removed here (Eigen, no flexmbs constraint code), through
// the fixed-interface and Craig-Bampton bases and the DOF list of the distributed path; the
// body file's `supports:` entries and their one-line errors.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <unistd.h>

#include "basis_test_support.h"
#include "reduction/craig_bampton.h"
#include "reduction/interior_problem.h"
#include "reduction/modal_basis.h"
#include "reduction/reduction_spec.h"
#include "tests/fem/test_meshes.h"
#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

namespace fs = std::filesystem;
using testing::Body;

constexpr double kLength = 1.2;
constexpr double kHeight = 0.1;
constexpr int kModes = 6;
// Fixed-interface frequencies against the dense solve, relative: measured 5.4e-11 (the
// eigensolver's residual bound 1e-8 squared in the Rayleigh quotient, times the spread).
constexpr double kDenseAgreement = 5e-10;
// Craig-Bampton (every constraint mode of a mid-span node set, 12 resp. 36 fixed-interface
// modes) is a Rayleigh-Ritz upper bound of the same problem: measured lowest-6 relative errors
// 3.9e-3 resp. 2.9e-5.
constexpr double kCraigBamptonAgreement12 = 4e-2;
constexpr double kCraigBamptonAgreement36 = 3e-4;

// The beam [0, 1.2] x [0, 0.1] x [0, 0.1] m, hex8 12 x 2 x 2, steel.
Body Beam() { return testing::MakeBox(fem::ElementType::kHex8, {12, 2, 2}, {kLength, kHeight, kHeight}, testing::Steel()); }

std::vector<int> Root(const Body& b) { return testing::NodesAt(b.mesh, 0, 0.0); }
// The tip's bottom edge line: x = L, z = 0 (along y).
std::vector<int> TipEdge(const Body& b) {
  return testing::NodesWhere(b.mesh, [](const Eigen::Vector3d& x) {
    return std::abs(x(0) - kLength) < 1e-9 && std::abs(x(2)) < 1e-9;
  });
}

// Root clamped, tip edge held in z.
BoundaryConditions RootAndEdgeInZ(const Body& b) {
  BoundaryConditions c;
  c.supports.push_back({"root", Root(b)});
  c.supports.push_back({"edge", TipEdge(b), {false, false, true}});
  return c;
}

// The held DOF built here by hand: 3 n + 0, 1, 2 of the root, 3 n + 2 of the edge; ascending.
std::vector<int> HandHeldDofs(const Body& b) {
  std::vector<int> dofs;
  for (const int n : Root(b)) {
    for (int a = 0; a < 3; ++a) dofs.push_back(3 * n + a);
  }
  for (const int n : TipEdge(b)) dofs.push_back(3 * n + 2);
  std::sort(dofs.begin(), dofs.end());
  return dofs;
}

// The lowest `count` frequencies [Hz] of K, M with the DOF in `held` removed: a dense
// generalized symmetric eigen-solve (Eigen).
Eigen::VectorXd DenseFrequencies(const Body& b, const std::vector<int>& held, int count) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index dof = 0; dof < b.K.rows(); ++dof) {
    if (!std::binary_search(held.begin(), held.end(), static_cast<int>(dof))) free.push_back(dof);
  }
  const Eigen::MatrixXd K = Eigen::MatrixXd(b.K)(free, free);
  const Eigen::MatrixXd M = Eigen::MatrixXd(b.M)(free, free);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(K, M, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().head(count).cwiseSqrt() / (2.0 * std::numbers::pi);
}

double LargestRelativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return ((a - b).array() / b.array()).abs().maxCoeff();
}

TEST(ComponentSupports, FixedInterfaceModesMatchADenseSolveWithTheHeldRowsRemovedByHand) {
  const Body b = Beam();
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = kModes;
  const ReducedBasis basis = FixedInterfaceModalBasis(b.model(), RootAndEdgeInZ(b), eigen, testing::Spectra());
  const Eigen::VectorXd dense = DenseFrequencies(b, HandHeldDofs(b), kModes);
  const double difference = LargestRelativeDifference(basis.frequency_hz, dense);
  std::printf("[measured] z-held edge: f1 %.4f Hz, largest relative difference to the dense solve %.2e\n",
              dense(0), difference);
  EXPECT_LT(difference, kDenseAgreement);
  // Held along z only: the edge's z rows are zero in every mode, its x and y rows are not.
  double z_rows = 0.0, xy_rows = 0.0;
  for (const int n : TipEdge(b)) {
    z_rows = std::max(z_rows, basis.Phi.row(3 * n + 2).cwiseAbs().maxCoeff());
    xy_rows = std::max(xy_rows, basis.Phi.middleRows(3 * n, 2).cwiseAbs().maxCoeff());
  }
  EXPECT_EQ(z_rows, 0.0);
  EXPECT_GT(xy_rows, 0.0);
  // And it is not the clamped edge: the first mode held in z only is the sideways (y) bending
  // the edge leaves free; clamping the edge raises f1 from 69.5 to 331 Hz (measured).
  std::vector<int> clamped = HandHeldDofs(b);
  for (const int n : TipEdge(b)) clamped.insert(clamped.end(), {3 * n, 3 * n + 1});
  std::sort(clamped.begin(), clamped.end());
  const double f1_clamped = DenseFrequencies(b, clamped, 1)(0);
  std::printf("[measured] the edge clamped instead: f1 %.4f Hz (+%.2f %%)\n", f1_clamped,
              100.0 * (f1_clamped / dense(0) - 1.0));
  EXPECT_GT(f1_clamped, dense(0) * (1.0 + 1e-3));
}

// The lowest kModes frequencies [Hz] of the Craig-Bampton basis of `c` with `normal_modes`.
Eigen::VectorXd CraigBamptonFrequencies(const Body& b, const BoundaryConditions& c, int normal_modes) {
  eigensolvers::EigenOptions normal;
  normal.num_modes = normal_modes;
  const ReducedBasis basis = CraigBamptonBasis(b.model(), c, normal, testing::Spectra());
  for (const int n : TipEdge(b)) EXPECT_EQ(basis.Phi.row(3 * n + 2).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> reduced(basis.K_reduced, basis.M_reduced,
                                                                          Eigen::EigenvaluesOnly);
  return reduced.eigenvalues().head(kModes).cwiseSqrt() / (2.0 * std::numbers::pi);
}

TEST(ComponentSupports, CraigBamptonConvergesToTheDenseSolveWithTheInterfaceFree) {
  const Body b = Beam();
  BoundaryConditions c = RootAndEdgeInZ(b);
  InterfaceSpec mid;
  mid.name = "mid";
  mid.nodes = testing::NodesAt(b.mesh, 0, 0.5 * kLength);
  c.interfaces.push_back(mid);
  const Eigen::VectorXd dense = DenseFrequencies(b, HandHeldDofs(b), kModes);
  const Eigen::VectorXd f12 = CraigBamptonFrequencies(b, c, 12);
  const Eigen::VectorXd f36 = CraigBamptonFrequencies(b, c, 36);
  const double e12 = LargestRelativeDifference(f12, dense), e36 = LargestRelativeDifference(f36, dense);
  std::printf("[measured] Craig-Bampton with the z-held edge: largest relative difference %.2e (12 normal modes), "
              "%.2e (36)\n", e12, e36);
  EXPECT_LT(e12, kCraigBamptonAgreement12);
  EXPECT_LT(e36, kCraigBamptonAgreement36);
  // Upper bounds, to the dense solve's round-off.
  EXPECT_GE((f12 - dense).minCoeff(), -kDenseAgreement * dense.maxCoeff());
  EXPECT_GE((f36 - dense).minCoeff(), -kDenseAgreement * dense.maxCoeff());
}

TEST(ComponentSupports, SupportsSharingNodesHoldTheUnionOfTheirComponents) {
  const Body b = Beam();
  BoundaryConditions c = RootAndEdgeInZ(b);
  // The edge's nodes again, held in y: z from the first, y from the second; the root's nodes
  // again in x add nothing.
  c.supports.push_back({"edge_y", TipEdge(b), {false, true, false}});
  c.supports.push_back({"root_x", Root(b), {true, false, false}});
  std::vector<int> held = HandHeldDofs(b);
  for (const int n : TipEdge(b)) held.push_back(3 * n + 1);
  std::sort(held.begin(), held.end());
  EXPECT_EQ(BuildConstraintTransform(b.mesh.nodes, c).num_support_dofs, static_cast<Eigen::Index>(held.size()));
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = kModes;
  const ReducedBasis basis = FixedInterfaceModalBasis(b.model(), c, eigen, testing::Spectra());
  const double difference = LargestRelativeDifference(basis.frequency_hz, DenseFrequencies(b, held, kModes));
  std::printf("[measured] edge held in y and z by two supports: largest relative difference %.2e\n", difference);
  EXPECT_LT(difference, kDenseAgreement);
  // A node listed twice in one support is still an error.
  c.supports[2].nodes.push_back(TipEdge(b)[0]);
  testing::ExpectInputError([&] { BuildConstraintTransform(b.mesh.nodes, c); },
                            {"support 'edge_y': node", "is listed twice"});
}

TEST(ComponentSupports, TheDistributedPathClampsExactlyTheHeldComponents) {
  const Body b = Beam();
  const std::optional<std::vector<int>> dofs = ClampedDofs(b.mesh.nodes, RootAndEdgeInZ(b));
  ASSERT_TRUE(dofs.has_value());
  EXPECT_EQ(*dofs, HandHeldDofs(b));
  const ConstraintTransform t = BuildConstraintTransform(b.mesh.nodes, RootAndEdgeInZ(b));
  EXPECT_EQ(t.num_support_dofs, static_cast<Eigen::Index>(HandHeldDofs(b).size()));
}

TEST(ComponentSupports, ASupportHoldingNothingOrOnlySomeComponentsOfAFreeBodyIsRefusedInOneLine) {
  const Body b = Beam();
  BoundaryConditions nothing;
  nothing.supports.push_back({"edge", TipEdge(b), {false, false, false}});
  testing::ExpectInputError([&] { BuildConstraintTransform(b.mesh.nodes, nothing); },
                            {"support 'edge': holds no component"});
  BoundaryConditions z_only;
  z_only.supports.push_back({"bottom", testing::NodesAt(b.mesh, 2, 0.0), {false, false, true}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 2;
  testing::ExpectInputError([&] { FixedInterfaceModalBasis(b.model(), z_only, eigen, testing::Spectra()); },
                            {"support 'bottom' does not hold the body", "hold only some components"});
}

// A body file with `reduction_yaml` in a folder of its own (CTest runs tests concurrently).
fs::path WriteBody(const std::string& reduction_yaml) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       (std::string("flexmbs_component_supports_") + test->name() + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "body.yaml";
  std::ofstream(path) << "name: b\nreduction:\n  method: fixed_interface\n  modes: 4\n" << reduction_yaml;
  return path;
}

const std::vector<std::string> kNodeSets = {"clamp", "edges"};

TEST(ComponentSupports, ABodyFileNamesSetsPlainlyOrWithTheirComponents) {
  const ReductionSpec spec = LoadReductionSpec(
      WriteBody("  supports: [clamp, {node_set: edges, components: [z, x]}]\n"), kNodeSets);
  ASSERT_EQ(spec.supports.size(), 2u);
  EXPECT_EQ(spec.supports[0].node_set, "clamp");
  EXPECT_EQ(spec.supports[0].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(spec.supports[1].node_set, "edges");
  EXPECT_EQ(spec.supports[1].components, (std::array<bool, 3>{true, false, true}));
  const BoundaryConditions c = ResolveConditions(spec, {{"clamp", {0, 1}}, {"edges", {2}}});
  ASSERT_EQ(c.supports.size(), 2u);
  EXPECT_EQ(c.supports[1].nodes, std::vector<int>{2});
  EXPECT_EQ(c.supports[1].components, (std::array<bool, 3>{true, false, true}));
  // Without components the map form holds all three.
  EXPECT_EQ(LoadReductionSpec(WriteBody("  supports: [{node_set: edges}]\n"), kNodeSets).supports[0].components,
            (std::array<bool, 3>{true, true, true}));
}

TEST(ComponentSupports, BadSupportEntriesGiveOneLineErrorsNamingItemAndValue) {
  auto error = [](const std::string& yaml) {
    return testing::InputErrorMessage([&] { LoadReductionSpec(WriteBody(yaml), kNodeSets); });
  };
  const std::string file = WriteBody("").string();
  EXPECT_EQ(error("  supports: [{node_set: edges, components: [z, w]}]\n"),
            file + ":5:48: reduction.supports[0].components[1]: 'w' must be one of: x, y, z");
  EXPECT_EQ(error("  supports: [{node_set: edges, components: []}]\n"),
            file + ":5:44: reduction.supports[0].components: an empty list holds nothing: give x, y and/or z");
  EXPECT_EQ(error("  supports: [{node_set: edges, components: [z, y, z]}]\n"),
            file + ":5:51: reduction.supports[0].components[2]: 'z' is listed twice");
  EXPECT_EQ(error("  supports: [{node_set: sides, components: [z]}]\n"),
            file + ":5:25: reduction.supports[0].node_set: 'sides' is not one of the body's node_sets (clamp, edges)");
  EXPECT_EQ(error("  supports: [{node_set: edges, component: [z]}]\n"),
            file + ":5:32: reduction.supports[0].component: unknown key 'component' (expected one of: node_set, components)");
  EXPECT_EQ(error("  supports: [{components: [z]}]\n"),
            file + ":5:14: reduction.supports[0]: missing key 'node_set'");
}

}  // namespace
}  // namespace flexmbs::reduction
