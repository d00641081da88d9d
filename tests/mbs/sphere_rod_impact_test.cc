// A steel sphere striking the end of an elastic steel rod (issue 16; the classical test of Hertz
// contact with wave propagation: Goldsmith, "Impact", 1960, §4.6; Seifried, Schiehlen & Eberhard,
// "Numerical and experimental evaluation of the coefficient of restitution for repeated impacts",
// IJIE 2005): the rod a reduced flexible body, the contact the compliant sphere_surface element
// with Hertz's law on the rod's end face, integrated by the implicit ODE method — against the full
// FE model of the same mesh with the same Hertz spring, integrated without any multibody code
// (tests/mbs/hertz_rod_model.h) at a step far below the contact's time scales.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <span>
#include <vector>

#include "contact/laws/hertz.h"
#include "contact/laws/normal_law.h"
#include "eigensolvers/eigensolver.h"
#include "fem/assembly.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/surface_contact_force.h"
#include "reduction/correction_modes.h"
#include "reduction/modal_basis.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/mbs/hertz_rod_model.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using testing::FeReducedBody;

constexpr double kLength = 0.5, kSide = 0.02;  // rod [m]
constexpr int kCellsAlong = 100;
constexpr double kRadius = 0.01;  // sphere [m]
constexpr double kSpeed = 1.0;    // [m/s]
constexpr double kEndTime = 120e-6, kOutput = 0.25e-6;  // [s]

double SphereMass() { return flexmbs::testing::Steel().density_kg_m3 * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3); }

double HertzStiffness() {
  const fem::IsotropicMaterial steel = flexmbs::testing::Steel();
  const contact::ElasticMaterial material{steel.youngs_modulus_pa, steel.poisson_ratio};
  return contact::HertzStiffness(contact::EffectiveModulus(material, material), kRadius);
}

/// The rod, its free-free modes below the 16.5th axial frequency c / (2L), contact surface "end"
/// (the face x = 0).
const FeReducedBody& Rod() {
  static const FeReducedBody rod = [] {
    FeReducedBody fe;
    fe.mesh = flexmbs::testing::HexBox(Eigen::Vector3i(kCellsAlong, 1, 1), Eigen::Vector3d(kLength, kSide, kSide),
                                       flexmbs::testing::Steel());
    fe.mesh.node_sets["end"] = flexmbs::testing::NodesOnPlane(fe.mesh, 0, 0.0);
    fem::SystemMatrices system = fem::AssembleSystem(fe.mesh, fem::MassMatrixKind::kConsistent);
    fe.K = std::move(system.stiffness);
    fe.M = std::move(system.mass);
    fe.sid_spec.contact_surfaces = {"end"};
    fe.sid_spec.geometric_stiffening = false;
    const fem::IsotropicMaterial steel = flexmbs::testing::Steel();
    reduction::FreeFreeOptions options;
    options.eigen.max_frequency_hz = 16.5 * std::sqrt(steel.youngs_modulus_pa / steel.density_kg_m3) / (2.0 * kLength);
    options.eigen.num_modes = 400;
    const std::unique_ptr<eigensolvers::Eigensolver> solver = eigensolvers::MakeEigensolver("spectra");
    fe.basis = reduction::FreeFreeModalBasis({fe.K, fe.M, fe.mesh.nodes}, options, *solver);
    return fe;
  }();
  return rod;
}

/// The contact point's weights on the FE DOFs: the end face's centre, the mean of its four
/// nodes, along x.
Eigen::VectorXd ContactWeights(const FeReducedBody& fe) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(fe.K.rows());
  const std::vector<int>& end = fe.mesh.node_sets.at("end");
  for (int node : end) b(3 * node) = 1.0 / static_cast<double>(end.size());
  return b;
}

/// The elastic modes the contact load excites (modal force b^T phi above 1e-6 of the largest),
/// ascending: the axial ones (bending and torsion vanish by symmetry).
std::vector<Index> LoadedModes(const FeReducedBody& fe) {
  const Eigen::VectorXd b = ContactWeights(fe);
  const std::vector<Index> elastic = testing::ElasticColumns(fe.basis);
  double largest = 0.0;
  for (Index j : elastic) largest = std::max(largest, std::abs(b.dot(fe.basis.Phi.col(j))));
  std::vector<Index> loaded;
  for (Index j : elastic) {
    if (std::abs(b.dot(fe.basis.Phi.col(j))) > 1e-6 * largest) loaded.push_back(j);
  }
  return loaded;
}

/// A force history on the output times k kOutput, k = 1, 2, ...
struct ForceHistory {
  std::vector<double> force;
  double seconds = 0.0;
  double highest_mode_hz = 0.0;
};

/// The full FE model's force at the output times (every 20th of its steps of kOutput / 20).
ForceHistory FullModel() {
  const FeReducedBody& fe = Rod();
  const testing::HertzImpactModel model{fe.K, fe.M, ContactWeights(fe), SphereMass(), HertzStiffness(), 0.0};
  const int substeps = 20;
  const testing::HertzImpactHistory run = testing::IntegrateHertzImpact(model, kSpeed, kOutput / substeps, kEndTime);
  ForceHistory history;
  for (std::size_t k = substeps - 1; k < run.force.size(); k += substeps) history.force.push_back(run.force[k]);
  history.seconds = run.seconds;
  return history;
}

/// The rod's lowest `modes` loaded modes, with the static correction mode of an axial load on the
/// end face (reduction/correction_modes.h: its inertia-relief response, M-orthogonalised) if
/// `correction`.
reduction::ReducedBasis RodBasis(int modes, bool correction) {
  const FeReducedBody& fe = Rod();
  const std::vector<Index> loaded = LoadedModes(fe);
  const reduction::ReducedBasis basis =
      testing::KeepColumns(fe.basis, std::vector<Index>(loaded.begin(), loaded.begin() + modes));
  if (!correction) return basis;
  const reduction::LoadSet end{"end", fe.mesh.node_sets.at("end"), Eigen::Vector3d::UnitX(),
                               reduction::LoadDistribution::kResultant, {}};
  return reduction::AddStaticCorrectionModes({fe.K, fe.M, fe.mesh.nodes}, basis, std::span(&end, 1)).basis;
}

/// The reduced rod (RodBasis) and the sphere, touching at t = 0, by the implicit method at
/// relative tolerance rtol.
ForceHistory Reduced(int modes, bool correction, double rtol) {
  const FeReducedBody& fe = Rod();
  const reduction::ReducedBasis basis = RodBasis(modes, correction);
  sid::ReducedBody data = testing::Reduce(fe, basis);
  data.name = "rod";
  const Index num_modes = basis.num_modes();
  const sid::ContactSurface end = data.surfaces.at(0);
  ForceHistory history;
  history.highest_mode_hz = data.frequency_hz(modes - 1);

  MultibodySystem system(Eigen::Vector3d::Zero());
  const int rod = system.AddBody(std::make_unique<FlexibleBody>("rod", std::move(data), false));
  const double inertia = 0.4 * SphereMass() * kRadius * kRadius;
  const int ball = system.AddBody(std::make_unique<RigidBody>("ball", SphereMass(), Eigen::Vector3d::Zero(),
                                                              inertia * Eigen::Matrix3d::Identity(),
                                                              std::vector<RigidBodyMarker>{{"centre"}}));
  auto element = std::make_unique<SphereSurfaceContact>(
      "hit", MarkerRef::OnBody(ball, 0), kRadius,
      MarkerRef::OnBody(rod, system.body(rod).FindMarker(FlexibleBody::kOriginMarker)), end,
      num_modes, CompliantContactLaw{contact::HertzLaw(HertzStiffness()), {}});
  const SphereSurfaceContact* hit = element.get();
  system.AddForceElement(std::move(element));
  Eigen::VectorXd y0 = system.NeutralState();
  y0.segment<3>(system.position_offset(ball)) = Eigen::Vector3d(-kRadius, 0.5 * kSide, 0.5 * kSide);
  y0(system.num_positions() + system.velocity_offset(ball)) = kSpeed;

  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = rtol;
  options.integrator.absolute_tolerance = 1e-6 * rtol;
  options.end_time = kEndTime;
  options.output_interval = kOutput;
  const auto start = std::chrono::steady_clock::now();
  Simulate(system, options, y0, [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
    if (t > 0.0) history.force.push_back(hit->NormalForce(t, system, y));
  });
  history.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return history;
}

double Peak(const ForceHistory& history) { return *std::max_element(history.force.begin(), history.force.end()); }

/// The time from the first output with force to the last [s].
double Duration(const ForceHistory& history) {
  std::size_t first = 0, last = 0;
  for (std::size_t k = 0; k < history.force.size(); ++k) {
    if (history.force[k] > 0.0) {
      if (last == 0) first = k;
      last = k + 1;
    }
  }
  return static_cast<double>(last - first) * kOutput;
}

/// max_k |a_k - b_k| / max_k b_k over the common outputs.
double HistoryError(const ForceHistory& a, const ForceHistory& b) {
  double largest = 0.0;
  for (std::size_t k = 0; k < std::min(a.force.size(), b.force.size()); ++k) {
    largest = std::max(largest, std::abs(a.force[k] - b.force[k]));
  }
  return largest / Peak(b);
}

TEST(SphereRodImpact, ReducedRodMatchesTheFullFeModelOnceTheContactsModesAreKept) {
  const ForceHistory full = FullModel();
  const double m = SphereMass(), k = HertzStiffness();
  // Hertz on a rigid half-space (Johnson, "Contact Mechanics", 1985, §11.4): the scale of the
  // contact time.
  const double t_hertz = 2.94 * std::pow(5.0 * m * kSpeed * kSpeed / (4.0 * k), 0.4) / kSpeed;
  std::printf("sphere r = %g m, m = %.4g kg on a %g m rod at %g m/s: full FE peak %.5g N over %.4g us (Hertz on a "
              "half-space: %.4g us), %.3f s\n",
              kRadius, m, kLength, kSpeed, Peak(full), 1e6 * Duration(full), 1e6 * t_hertz, full.seconds);
  std::printf("%6s %12s %12s %12s %12s %10s %9s\n", "modes", "f_max t_c", "peak", "duration", "history", "cpu [s]",
              "speed-up");
  const std::vector<int> mode_counts{2, 4, 8, 16};
  // peak_error[c][i], history_error[c][i]: without (c = 0) and with (c = 1) the correction mode.
  std::array<std::vector<double>, 2> peak_error, history_error;
  std::array<int, 2> enough{0, 0};  // the fewest modes for a peak force within 1 %
  for (const bool correction : {false, true}) {
    for (int modes : mode_counts) {
      const ForceHistory reduced = Reduced(modes, correction, 1e-8);
      peak_error[correction].push_back(std::abs(Peak(reduced) / Peak(full) - 1.0));
      history_error[correction].push_back(HistoryError(reduced, full));
      if (enough[correction] == 0 && peak_error[correction].back() <= 0.01) enough[correction] = modes;
      std::printf("%4d%2s %12.3f %+12.3e %+12.3e %12.3e %10.3f %9.1f\n", modes, correction ? "+c" : "",
                  reduced.highest_mode_hz * t_hertz, Peak(reduced) / Peak(full) - 1.0,
                  Duration(reduced) / Duration(full) - 1.0, history_error[correction].back(), reduced.seconds,
                  full.seconds / reduced.seconds);
    }
  }
  std::printf("modes for a peak force within 1 %%: %d, with the end face's correction mode %d\n", enough[0], enough[1]);
  // The rule of docs/contact.md ("Which modes a contact needs") rests on these counts: the
  // loaded modes up to f_max = 3 / t_c alone, up to 1.5 / t_c with the correction mode.
  EXPECT_EQ(enough[0], 8);
  EXPECT_EQ(enough[1], 4);
  for (std::size_t i = 0; i < mode_counts.size(); ++i) {
    SCOPED_TRACE(mode_counts[i]);
    // The correction mode always helps (measured: 4.1e-2 -> 1.4e-2 at 2 modes, 3.5e-3 ->
    // 1.3e-5 at 16).
    EXPECT_LT(peak_error[1][i], peak_error[0][i]);
    EXPECT_LT(history_error[1][i], history_error[0][i]);
    if (i == 0) continue;
    // Without it the peak error halves per doubling of the modes (measured ratios 0.42-0.47).
    EXPECT_LT(peak_error[0][i], 0.6 * peak_error[0][i - 1]);
  }
  // Converged with 16 loaded modes and the correction mode (measured: peak 1.3e-5, history
  // 1.4e-4 of the peak force).
  EXPECT_LT(peak_error[1].back(), 1.3e-4);
  EXPECT_LT(history_error[1].back(), 1.4e-3);
}

}  // namespace
}  // namespace flexmbs::mbs
