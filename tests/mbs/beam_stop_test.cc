// A free elastic beam striking a rigid stop near its tip (issue 16, the thesis' kind of example:
// an eccentric transverse impact exciting bending and rigid rotation): the beam reduced to its
// free-free modes with the stop a surface_plane contact (Moreau-Jean, e = 0 at the points) against
// the full FE model stepped by the same theta method without any multibody code
// (tests/mbs/linear_impact_model.h; small rotations over the run: 5e-3 rad), over the modes kept,
// with and without the pad's static correction mode. The test prints the table. Measured: the
// impulse history approaches the full model's (0.111, 0.094, 0.080, 0.076 of m v for 4, 8, 16,
// 32 modes) but floors near 0.076 with or without the correction mode, the total impulse 4-7 %
// low: the full model's contact nodes carry their own small masses and stop at 1 us steps, which
// no band of global modes below 40 kHz reproduces (docs/contact.md). An open question, asserted
// only as far as it holds: more modes, closer.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <cstdio>
#include <memory>
#include <span>
#include <vector>

#include "mbs/flexible_body.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/surface_unilateral.h"
#include "reduction/correction_modes.h"
#include "reduction/modal_basis.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/mbs/linear_impact_model.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using testing::FeReducedBody;

constexpr double kLength = 0.6, kSide = 0.04;  // [m]
constexpr double kSpeed = 1.0;                  // [m/s], along -y
constexpr double kEndTime = 1e-3, kStep = 1e-6;  // [s]

/// The beam (30 x 2 x 2 hex8, steel) with the node set "pad": the nodes of its face y = 0 in the
/// last cell before the tip; its free-free modes below 40 kHz.
const FeReducedBody& Beam() {
  static const FeReducedBody beam = testing::FreeFreeBox(
      Eigen::Vector3i(30, 2, 2), Eigen::Vector3d(kLength, kSide, kSide), flexmbs::testing::Steel(),
      [](const fem::Mesh& mesh) {
        std::vector<int> pad;
        for (int node : flexmbs::testing::NodesOnPlane(mesh, 1, 0.0)) {
          if (mesh.nodes(0, node) >= kLength - kLength / 30.0 - 1e-12) pad.push_back(node);
        }
        return std::map<std::string, std::vector<int>>{{"pad", pad}};
      },
      {"pad"}, 40e3);
  return beam;
}

/// A run's contact impulses per step and its wall time.
struct StopRun {
  std::vector<double> impulse;
  double seconds = 0.0;
};

/// The full FE model: every pad node a contact on its y displacement (gap y = 0 at rest).
StopRun FullModel() {
  const FeReducedBody& fe = Beam();
  const std::vector<int>& pad = fe.mesh.node_sets.at("pad");
  testing::LinearContactModel model{fe.K, fe.M, Eigen::MatrixXd::Zero(static_cast<Index>(pad.size()), fe.K.rows()),
                                    Eigen::VectorXd::Zero(static_cast<Index>(pad.size()))};
  for (std::size_t c = 0; c < pad.size(); ++c) model.H(static_cast<Index>(c), 3 * pad[c] + 1) = 1.0;
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(fe.K.rows());
  for (Index node = 0; node < fe.mesh.num_nodes(); ++node) v0(3 * node + 1) = -kSpeed;
  const testing::LinearImpactHistory history = testing::IntegrateLinearImpact(model, v0, kStep, kEndTime);
  return {history.impulse, history.seconds};
}

/// The reduced beam with its lowest `modes` elastic modes, and the static correction mode of a
/// load along y on the pad if `correction`, against the stop y = 0 (normal +y).
StopRun Reduced(int modes, bool correction) {
  const FeReducedBody& fe = Beam();
  std::vector<Index> elastic = testing::ElasticColumns(fe.basis);
  elastic.resize(static_cast<std::size_t>(modes));
  reduction::ReducedBasis basis = testing::KeepColumns(fe.basis, elastic);
  if (correction) {
    const reduction::LoadSet pad{"pad", fe.mesh.node_sets.at("pad"), Eigen::Vector3d::UnitY(),
                                 reduction::LoadDistribution::kResultant, {}};
    basis = reduction::AddStaticCorrectionModes({fe.K, fe.M, fe.mesh.nodes}, basis, std::span(&pad, 1)).basis;
  }
  const Index kept = basis.num_modes();
  sid::ReducedBody data = testing::Reduce(fe, basis);
  data.name = "beam";
  const sid::ContactSurface pad = data.surfaces.at(0);
  MultibodySystem system(Eigen::Vector3d::Zero());
  const int beam = system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), false));
  Eigen::Matrix3d R_WP;  // the stop's z axis along +y
  R_WP << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  system.AddUnilateralContact(std::make_unique<SurfacePlaneUnilateral>(
      "stop", MarkerRef::OnBody(beam, system.body(beam).FindMarker(FlexibleBody::kOriginMarker)), pad,
      kept, MarkerRef::Ground(Eigen::Vector3d::Zero(), R_WP), UnilateralLaw{}));
  Eigen::VectorXd y = system.NeutralState();
  y(system.num_positions() + system.velocity_offset(beam) + 1) = -kSpeed;
  MoreauJeanOptions options;
  options.step = kStep;
  MoreauJeanStepper stepper(system, options);
  StopRun run;
  const auto start = std::chrono::steady_clock::now();
  for (double t = 0.0; t < kEndTime; t += kStep) run.impulse.push_back(stepper.Step(t, kStep, y).contacts[0].P_N);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

double Sum(const std::vector<double>& values) {
  double sum = 0.0;
  for (double value : values) sum += value;
  return sum;
}

TEST(BeamStop, ReducedBeamApproachesTheFullFeModelsImpulseHistoryUpToAFloor) {
  const StopRun full = FullModel();
  const double momentum = Beam().M.sum() / 3.0 * kSpeed;  // m v: M's entries sum to 3 m
  std::printf("beam %g x %g x %g m at %g m/s on a stop under its tip: full FE model (%lld DOF) impulse %.6g N s "
              "(%.4f m v) over %g ms, %.3f s\n",
              kLength, kSide, kSide, kSpeed, static_cast<long long>(Beam().K.rows()), Sum(full.impulse),
              Sum(full.impulse) / momentum, 1e3 * kEndTime, full.seconds);
  std::printf("%6s %12s %14s %10s %9s\n", "modes", "impulse", "history error", "cpu [s]", "speed-up");
  std::array<std::vector<double>, 2> errors;  // without, with the correction mode
  for (const bool correction : {false, true}) {
    for (int modes : {4, 8, 16, 32}) {
      const StopRun reduced = Reduced(modes, correction);
      errors[correction].push_back(testing::LargestCumulativeDifference(reduced.impulse, full.impulse) / momentum);
      std::printf("%4d%2s %+12.3e %14.3e %10.3f %9.1f\n", modes, correction ? "+c" : "",
                  Sum(reduced.impulse) / Sum(full.impulse) - 1.0, errors[correction].back(), reduced.seconds,
                  full.seconds / reduced.seconds);
    }
  }
  for (std::size_t k = 1; k < errors[0].size(); ++k) EXPECT_LT(errors[0][k], errors[0][k - 1]);
  EXPECT_LT(errors[0].back(), 0.08);  // measured 0.076
  EXPECT_LT(errors[1].back(), 0.08);  // measured 0.076
}

}  // namespace
}  // namespace flexmbs::mbs
