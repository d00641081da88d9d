// The distributed path after the eigen-solve, on one rank and on two: the same eigenpairs
// (from SolveModesDistributed) finished into a basis, correction modes and the SID data once
// through the kept distributed matrices (DistributedModel: products and MUMPS static solves,
// no assembled K and M) and once through the serial K and M on rank 0, the way `reduce` did it
// before. Both must give the same body to round-off, and the distributed way must make no
// serial factorisation: a held body's static solves use the eigen-solve's factorisation of K_oo
// (two MUMPS factorisations in all, the Sturm count's the other), a free body's make one of
// their own.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>

#include "fem/assembly.h"
#include "reduction/correction_modes.h"
#include "reduction/distributed_reduction.h"
#include "reduction/interior_problem.h"
#include "reduction/modal_basis.h"
#include "eigensolvers/shifted_factorization.h"
#include "reduction/sid_body_builder.h"
#include "reduction/sid_spec.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "tests/eigensolvers/petsc_log_count.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

// Frequencies: the bound for the distributed products against the serial ones (the
// eigenpairs are the same; only the order of the sums differs). Measured: below 1e-14.
constexpr double kFrequencyAgreement = 1e-10;
// Everything else, relative to the largest entry of each array (of all the stiffening matrices
// for those that hold stiffening terms: some are zero to round-off, e.g. K0t of a free body,
// which inertia relief leaves unstressed): the bound for the invariants. The static
// responses come from MUMPS here and from CHOLMOD in the reference, so they agree to about eps
// times the condition number of K_ff (measured: below 1e-12).
constexpr double kAgreement = 1e-9;

int Rank() { return SlepcSession::Rank(); }

// The numeric Cholesky factorisations (MUMPS's and the substructured ones) PETSc's log has seen
// on this rank.
int LoggedFactorizations() {
  SubstructuredEvents();  // registered before they are counted
  return testing::LoggedEventCount("MatCholFctrNum") + testing::LoggedEventCount("SubstrFactor");
}

// A 10 x 3 x 2 hex8 steel bar 0.5 m long with node sets "root" (x = 0) and "tip" (x = 0.5).
fem::Mesh Bar() {
  fem::Mesh mesh = testing::HexBox({10, 3, 2}, {0.5, 0.15, 0.1}, testing::Steel());
  mesh.node_sets["root"] = testing::NodesOnPlane(mesh, 0, 0.0);
  mesh.node_sets["tip"] = testing::NodesOnPlane(mesh, 0, 0.5);
  return mesh;
}

// The `sid:` section: a rigid marker at the tip (loaded for the stiffening), modal damping.
reduction::SidSpec Sid() {
  reduction::SidSpec sid;
  reduction::MarkerSetting tip;
  tip.name = "tip_marker";
  tip.node_set = "tip";
  tip.coupling = reduction::MarkerCoupling::kRigid;
  sid.markers.push_back(tip);
  sid.damping.kind = reduction::DampingKind::kModal;
  sid.damping.modal_ratio = 0.02;
  return sid;
}

// max |a - b| / max(max |a|, scale) (0 for two empty arrays).
double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double scale = 0.0) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.size() == 0 || a.rows() != b.rows() || a.cols() != b.cols()) return 0.0;
  scale = std::max(scale, a.cwiseAbs().maxCoeff());
  return scale > 0.0 ? (a - b).cwiseAbs().maxCoeff() / scale : b.cwiseAbs().maxCoeff();
}

// The largest RelativeDifference over a Taylor block's orders; `stiffening_scale` for its
// orders 1 and 2.
double RelativeDifference(const sid::TaylorMatrix& a, const sid::TaylorMatrix& b, double stiffening_scale = 0.0) {
  EXPECT_EQ(a.m1.size(), b.m1.size());
  EXPECT_EQ(a.m2.size(), b.m2.size());
  double worst = RelativeDifference(a.m0, b.m0);
  for (const auto& [blocks_a, blocks_b] : {std::pair{&a.m1, &b.m1}, std::pair{&a.m2, &b.m2}}) {
    if (blocks_a->size() != blocks_b->size()) continue;
    Eigen::MatrixXd stacked_a(0, 0), stacked_b(0, 0);
    for (std::size_t k = 0; k < blocks_a->size(); ++k) {
      const Eigen::MatrixXd& x = (*blocks_a)[k];
      const Eigen::MatrixXd& y = (*blocks_b)[k];
      stacked_a.conservativeResize(x.rows(), stacked_a.cols() + x.cols());
      stacked_b.conservativeResize(y.rows(), stacked_b.cols() + y.cols());
      stacked_a.rightCols(x.cols()) = x;
      stacked_b.rightCols(y.cols()) = y;
    }
    worst = std::max(worst, RelativeDifference(stacked_a, stacked_b, stiffening_scale));
  }
  return worst;
}

// The serial body (reference) and the distributed one agree: frequencies to kFrequencyAgreement,
// every array of the SID data to kAgreement. Returns the largest difference of the arrays.
double ExpectSameBody(const sid::ReducedBody& serial, const sid::ReducedBody& distributed) {
  EXPECT_EQ(serial.mode_names, distributed.mode_names);
  EXPECT_EQ(serial.mode_kinds, distributed.mode_kinds);
  for (Eigen::Index k = 0; k < serial.frequency_hz.size(); ++k) {
    const double f = serial.frequency_hz(k);
    if (std::isnan(f)) {
      EXPECT_TRUE(std::isnan(distributed.frequency_hz(k))) << "mode " << k;
    } else if (f > 0.0) {
      EXPECT_NEAR(distributed.frequency_hz(k), f, kFrequencyAgreement * f) << "mode " << k;
    }
  }
  EXPECT_NEAR(distributed.mass, serial.mass, kAgreement * serial.mass);
  double worst = std::max(RelativeDifference(serial.center_of_mass, distributed.center_of_mass),
                          RelativeDifference(serial.inertia_about_center_of_mass,
                                             distributed.inertia_about_center_of_mass));
  worst = std::max(worst, RelativeDifference(serial.phi, distributed.phi));
  for (const auto& [a, b] : {std::pair{&serial.mdCM, &distributed.mdCM}, {&serial.J, &distributed.J},
                             {&serial.Me, &distributed.Me}, {&serial.Gr, &distributed.Gr},
                             {&serial.Ge, &distributed.Ge}, {&serial.Ke, &distributed.Ke},
                             {&serial.De, &distributed.De}}) {
    worst = std::max(worst, RelativeDifference(*a, *b));
  }
  const sid::GeometricStiffening& s = serial.stiffening;
  const sid::GeometricStiffening& d = distributed.stiffening;
  double stiffening_scale = 0.0;
  for (const Eigen::MatrixXd& K0 : s.K0t) stiffening_scale = std::max(stiffening_scale, K0.cwiseAbs().maxCoeff());
  for (const Eigen::MatrixXd& K0 : s.K0r) stiffening_scale = std::max(stiffening_scale, K0.cwiseAbs().maxCoeff());
  for (const Eigen::MatrixXd& K0 : s.K0omega) stiffening_scale = std::max(stiffening_scale, K0.cwiseAbs().maxCoeff());
  for (std::size_t a = 0; a < 3; ++a) {
    worst = std::max(worst, RelativeDifference(s.K0t[a], d.K0t[a], stiffening_scale));
    worst = std::max(worst, RelativeDifference(s.K0r[a], d.K0r[a], stiffening_scale));
  }
  for (std::size_t l = 0; l < 6; ++l) worst = std::max(worst, RelativeDifference(s.K0omega[l], d.K0omega[l], stiffening_scale));
  // Ct, Cr and Oe carry the stiffening in their order 1.
  for (const auto& [a, b] : {std::pair{&serial.Ct, &distributed.Ct}, {&serial.Cr, &distributed.Cr},
                             {&serial.Oe, &distributed.Oe}}) {
    worst = std::max(worst, RelativeDifference(*a, *b, stiffening_scale));
  }
  EXPECT_EQ(serial.nodes.size(), distributed.nodes.size());
  for (std::size_t k = 0; k < std::min(serial.nodes.size(), distributed.nodes.size()); ++k) {
    worst = std::max(worst, RelativeDifference(serial.nodes[k].phi, distributed.nodes[k].phi));
    worst = std::max(worst, RelativeDifference(serial.nodes[k].psi, distributed.nodes[k].psi));
  }
  EXPECT_LT(worst, kAgreement);
  return worst;
}

// A body through one FE model: the basis from `solution` (free-free if `held` is empty), static
// correction modes for a tip load, and the SID data.
sid::ReducedBody Finish(const fem::Mesh& mesh, const reduction::FeModel& model, fem::MassMatrixKind mass_kind,
                        const reduction::BoundaryConditions& held, const EigenOptions& eigen, const EigenSolution& solution) {
  reduction::ReducedBasis basis;
  if (held.empty()) {
    reduction::FreeFreeOptions options;
    options.eigen.num_modes = eigen.num_modes - 6;
    basis = reduction::FreeFreeModalBasis(model, options, solution);
  } else {
    basis = reduction::FixedInterfaceModalBasis(model, held, eigen, solution);
  }
  reduction::LoadSet tip_load;
  tip_load.name = "tip";
  tip_load.nodes = mesh.node_sets.at("tip");
  tip_load.direction = Eigen::Vector3d(0.0, 1.0, 0.3);
  const reduction::LoadSet loads[] = {tip_load};
  basis = reduction::AddStaticCorrectionModes(model, basis, loads).basis;
  return reduction::BuildReducedBody(mesh, model, mass_kind, Sid(), basis);
}

// Solves distributed, then finishes the body both ways on rank 0 (the other ranks serve the
// distributed products) and compares.
void ExpectDistributedFinishEqualsSerial(fem::MassMatrixKind mass_kind, const reduction::BoundaryConditions& held,
                                         const EigenOptions& eigen) {
  const fem::Mesh mesh = Bar();
  const fem::Mesh empty;
  const std::vector<int> clamped = *reduction::ClampedDofs(mesh.nodes, held);
  reduction::DistributedSolveStats solve_stats;
  std::unique_ptr<DistributedModel> distributed;
  const int factorizations_before = LoggedFactorizations();
  const EigenSolution solution = reduction::SolveModesDistributed(Rank() == 0 ? mesh : empty, mass_kind,
                                                       Rank() == 0 ? clamped : std::vector<int>{}, eigen,
                                                       &solve_stats, &distributed);
  ASSERT_TRUE(distributed);
  // A held body: the shift 0, K_oo and the Sturm count's K_oo - cut M factorised; a free body:
  // K - sigma M, refactorised at the cut.
  EXPECT_EQ(solution.shift == 0.0, !held.empty());
  EXPECT_EQ(solution.factorizations, 2);
  EXPECT_EQ(solution.missed_mode_check, MissedModeCheck::kSturmCount);
  if (Rank() != 0) {
    distributed->Serve();
    // Every rank took part in every factorisation: the eigen-solve's, and a free body's static one.
    EXPECT_EQ(LoggedFactorizations() - factorizations_before, held.empty() ? 3 : 2);
    return;
  }
  const int serial_factorizations = ShiftedFactorization::NumericFactorizations();
  sid::ReducedBody by_products;
  {
    const reduction::FeModel model(*distributed, mesh.nodes);
    by_products = Finish(mesh, model, mass_kind, held, eigen, solution);
  }
  const DistributedModelStats stats = distributed->Finish();
  // No serial factorisation on rank 0; one MUMPS factorisation served the correction modes and
  // the stiffening load cases: the eigen-solve's (held), or one of their own (inertia relief).
  EXPECT_EQ(ShiftedFactorization::NumericFactorizations(), serial_factorizations);
  EXPECT_EQ(stats.factorizations, held.empty() ? 1 : 0);
  EXPECT_EQ(LoggedFactorizations() - factorizations_before, solution.factorizations + stats.factorizations);
  EXPECT_GT(stats.static_solves, 12);
  EXPECT_GT(stats.product_columns, 0);
  ASSERT_EQ(stats.peak_rss_mb.size(), static_cast<std::size_t>(SlepcSession::Size()));
  for (double peak : stats.peak_rss_mb) EXPECT_GT(peak, 0.0);

  const fem::SystemMatrices system = fem::AssembleSystem(mesh, mass_kind);
  const sid::ReducedBody serial =
      Finish(mesh, reduction::FeModel(system.stiffness, system.mass, mesh.nodes), mass_kind, held, eigen, solution);
  EXPECT_GT(ShiftedFactorization::NumericFactorizations(), serial_factorizations);  // the counter sees them
  const double worst = ExpectSameBody(serial, by_products);
  std::ostringstream text;
  text << std::scientific << std::setprecision(2) << worst;
  ::testing::Test::RecordProperty("largest_relative_difference", text.str());
}

TEST(DistributedModel, HeldBarFinishedByProductsEqualsTheSerialMatrices) {
  reduction::BoundaryConditions held;
  held.supports.push_back({"root", Bar().node_sets.at("root")});
  EigenOptions eigen;
  eigen.num_modes = 6;
  ExpectDistributedFinishEqualsSerial(fem::MassMatrixKind::kConsistent, held, eigen);
}

TEST(DistributedModel, FreeLumpedBarFinishedByProductsEqualsTheSerialMatrices) {
  // Free-free: exact rigid modes, Rayleigh-Ritz and residuals from products, inertia relief by a
  // MUMPS solve with the 3-2-1 support; lumped: the invariants' consistent M assembled
  // distributed on demand.
  EigenOptions eigen;
  eigen.num_modes = 6 + 5;
  ExpectDistributedFinishEqualsSerial(fem::MassMatrixKind::kLumped, {}, eigen);
}

}  // namespace
}  // namespace flexmbs::eigensolvers
