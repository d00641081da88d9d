// mbs/spur_gear_contact on a flexible body: the wheel sits on the tip interface of a clamped
// Craig-Bampton beam, the pinion on a revolute joint turns slowly into it. At rest the pinion's
// turn along the line of action is shared by the mesh (F / (c' b n)) and the beam's tip, whose
// compliance along the line through the contact point comes from the FE model's stiffness
// condensed to the tip (the constraint modes, Phi_c^T K Phi_c): the mesh force reaches the
// body's modes as a load on the tip with its lever. Turned in quickly and held, the pinion leaves
// the beam ringing on the mesh: the tip's spectrum peaks at the natural frequencies of the
// reduced beam with the tooth pairs' springs on its tip (an eigen-solve beside the simulation).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/spur_gear_contact.h"
#include "mbs/time_function.h"
#include "sid/reduced_body.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;

/// The beam (body 0, clamped; `undamped`: its Rayleigh damping De left out), the pinion on a
/// revolute joint whose angle runs from the touching angle to `turn` [rad] past it by a quintic
/// step over `ramp` [s] and is held there, and the mesh (force element 0, teeth of c' = 1.4e10
/// N/m^2, no damping); the state at rest, touching.
struct GearOnBeam {
  MultibodySystem system{Vector3d::Zero()};
  contact::GearPair pair;
  MarkerRef tip;
  Vector3d p_tip = Vector3d::Zero();
  Eigen::VectorXd y0;
};

std::unique_ptr<GearOnBeam> BuildGearOnBeam(double ramp, double turn, bool undamped) {
  auto out = std::make_unique<GearOnBeam>();
  MultibodySystem& system = out->system;
  sid::ReducedBody beam = testing::CraigBamptonBeam().body;
  if (undamped) beam.De.m0.setZero();
  system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(beam), false));
  system.AddJoint(Joint("clamp", JointType::kFixed, MarkerRef::Ground(Vector3d::Zero()),
                        system.Marker("beam", FlexibleBody::kOriginMarker)));
  out->tip = system.Marker("beam", "tip");
  out->p_tip = system.MarkerState(out->tip, system.NeutralState()).p_WM_W;

  contact::GearPairSpec spec;
  spec.gear1 =
      contact::SpurGearSpec{2e-3, 19, 20.0 * std::numbers::pi / 180.0, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 =
      contact::SpurGearSpec{2e-3, 31, 20.0 * std::numbers::pi / 180.0, -0.1, 1.0, 1.25, 0.02};
  spec.centre_distance = 0.0505;
  out->pair = contact::MakeGearPair(spec);
  const Vector3d p_pinion = out->p_tip - Vector3d(0.0505, 0.0, 0.0);  // line of centres along +x
  system.AddBody(std::make_unique<RigidBody>(
      "pinion", 0.18, Vector3d::Zero(),
      Eigen::Vector3d(2e-5, 2e-5, 3.4e-5).asDiagonal().toDenseMatrix(),
      std::vector<RigidBodyMarker>{{"axis", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  // Wheel 1's touching angle with the wheel at 0 (dg/dphi1 = -r_b1 on the positive flanks).
  const double touch = contact::SmallestGap(contact::MeshingToothPairs(out->pair, 0.0505, 0.0, 0.0),
                                            contact::FlankSide::kPositive) /
                       out->pair.gear1.base_radius;
  system.AddJoint(Joint("pinion_axis", JointType::kRevolute, MarkerRef::Ground(p_pinion),
                        system.Marker("pinion", "axis"),
                        MakeSmoothStep(0.0, touch, ramp, touch + turn, SmoothStepOrder::kQuintic)));
  system.AddForceElement(std::make_unique<SpurGearContact>(
      "mesh", system.Marker("pinion", "axis"), out->tip, out->pair,
      contact::ToothPairLaw({1.4e10, 0.0}, out->pair)));
  out->y0 = system.NeutralState();
  Eigen::VectorXd x(7), u = Eigen::VectorXd::Zero(6);
  x << p_pinion, std::cos(touch / 2), 0.0, 0.0, std::sin(touch / 2);
  system.SetBodyState(1, x, u, out->y0);
  return out;
}

/// The columns of the tip's six constraint modes in the beam's basis (translations, rotations).
std::vector<Eigen::Index> TipColumns(const testing::FeReducedBody& fe) {
  std::vector<Eigen::Index> columns;
  for (const char* name : {"constraint_tip_tx", "constraint_tip_ty", "constraint_tip_tz",
                           "constraint_tip_rx", "constraint_tip_ry", "constraint_tip_rz"}) {
    const auto at = std::find(fe.basis.names.begin(), fe.basis.names.end(), name);
    EXPECT_NE(at, fe.basis.names.end()) << name;
    columns.push_back(at - fe.basis.names.begin());
  }
  return columns;
}

TEST(SpurGearOnFlexibleBody, PinionTurnIsSharedByTheMeshAndTheBeamsTipCompliance) {
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  // A quintic turn of 2e-3 rad into the mesh over 0.2 s, held to 0.35 s.
  const double turn = 2e-3;
  const std::unique_ptr<GearOnBeam> model = BuildGearOnBeam(0.2, turn, false);
  MultibodySystem& system = model->system;
  const contact::GearPair& pair = model->pair;
  const Vector3d p_tip = model->p_tip;
  const double k = 1.4e10 * 0.02;

  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = 1e-8;
  options.integrator.absolute_tolerance = 1e-12;
  options.end_time = 0.35;
  options.output_interval = 0.35;
  Eigen::VectorXd y_end;
  Simulate(system, options, model->y0,
           [&](double, const Eigen::VectorXd& y, const Eigen::VectorXd&) { y_end = y; });

  const auto& mesh = dynamic_cast<const SpurGearContact&>(system.force_element(0));
  const std::vector<ContactLoad> loads = mesh.ContactLoads(0.35, system, y_end);
  ASSERT_FALSE(loads.empty());
  double force = 0.0;
  for (const ContactLoad& load : loads) force += load.f_W.norm();
  const Vector3d n = loads.front().n_W, p_c = loads.front().p_W;

  // The tip's static compliance from the FE model: the stiffness condensed to the tip's six
  // interface coordinates (translations, rotations about the tip node) by its constraint modes.
  const Eigen::MatrixXd Phi_c = fe.basis.Phi(Eigen::all, TipColumns(fe));
  const Eigen::MatrixXd K_cc = Phi_c.transpose() * (fe.K * Phi_c);
  Eigen::Matrix<double, 6, 1> lever;  // the unit load along n at the contact point, at the tip node
  lever << n, (p_c - p_tip).cross(n);
  const double beam_compliance = lever.dot(K_cc.ldlt().solve(lever));
  const double mesh_compliance = 1.0 / (k * static_cast<double>(loads.size()));
  const double expected = pair.gear1.base_radius * turn / (mesh_compliance + beam_compliance);
  std::printf(
      "[measured] mesh force %.6g N against r_b1 turn / (1/(c' b n) + c_tip) = %.6g N (n = %zu, "
      "beam "
      "compliance %.3g m/N, mesh %.3g m/N): %.3g relative\n",
      force, expected, loads.size(), beam_compliance, mesh_compliance, force / expected - 1.0);
  EXPECT_NEAR(force / expected, 1.0, 7e-4);  // measured 6.7e-5 (the turning line and contact point)
}

/// The amplitude of the Hann-windowed discrete Fourier transform of the samples x at t [s] at
/// frequency f [Hz].
double Spectrum(const std::vector<double>& t, const std::vector<double>& x, double f) {
  std::complex<double> sum = 0.0;
  const double n = static_cast<double>(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double window = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * k / (n - 1.0));
    sum += window * x[k] * std::exp(std::complex<double>(0.0, -2.0 * std::numbers::pi * f * t[k]));
  }
  return std::abs(sum);
}

// The pinion turned 2e-3 rad into the mesh within 3 ms and held, the beam undamped: the beam rings
// on the mesh, which stays closed. The spectrum of its tip's motion along the line of action
// (3.5 ... 40 ms, Hann window) peaks where the beam's reduced model with every tooth pair in
// contact as a spring c' b on its tip (the pair's contact point and line of action as the lever
// of the tip's constraint modes) has its natural frequencies: (K_r + sum_p k_p l_p l_p^T) phi =
// omega^2 M_r phi, solved beside the simulation — not the beam's own (the mesh holds the tip).
TEST(SpurGearOnFlexibleBody, MeshExcitesTheBeamAtTheNaturalFrequenciesOfBeamAndMesh) {
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  const std::unique_ptr<GearOnBeam> model = BuildGearOnBeam(3e-3, 2e-3, true);
  MultibodySystem& system = model->system;
  const double alpha_w = model->pair.working_pressure_angle;
  const Vector3d n(std::sin(alpha_w), std::cos(alpha_w), 0.0);  // positive flanks' line of action
  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = 1e-9;
  options.integrator.absolute_tolerance = 1e-13;
  options.integrator.max_step = 1e-5;
  options.end_time = 0.04;
  options.output_interval = 1e-5;
  const auto& mesh = dynamic_cast<const SpurGearContact&>(system.force_element(0));
  std::vector<double> times, along;
  Eigen::VectorXd y_end;
  double least_force = 1e30;  // the mesh force's least value over the record [N]
  Simulate(system, options, model->y0,
           [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
             y_end = y;
             if (t < 3.5e-3) return;  // the turn
             times.push_back(t);
             along.push_back(n.dot(system.MarkerState(model->tip, y).p_WM_W - model->p_tip));
             least_force = std::min(least_force, mesh.MeshForce(t, system, y));
           });
  std::printf("[measured] mesh force over the record >= %.4g N (closed)\n", least_force);
  ASSERT_GT(least_force, 0.0);
  double mean = 0.0;
  for (const double x : along) mean += x / static_cast<double>(along.size());
  for (double& x : along) x -= mean;

  // The natural frequencies of the reduced beam with the pairs' springs on its tip.
  const std::vector<Eigen::Index> tip = TipColumns(fe);
  Eigen::MatrixXd K = fe.basis.K_reduced;
  for (const ContactLoad& load : mesh.ContactLoads(options.end_time, system, y_end)) {
    Eigen::VectorXd lever = Eigen::VectorXd::Zero(K.rows());
    Eigen::Matrix<double, 6, 1> at_tip;
    at_tip << load.n_W, (load.p_W - model->p_tip).cross(load.n_W);
    lever(tip) = at_tip;
    K += 1.4e10 * 0.02 * lever * lever.transpose();
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> coupled(K, fe.basis.M_reduced);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> alone(fe.basis.K_reduced,
                                                                        fe.basis.M_reduced);
  const auto hz = [](double lambda) { return std::sqrt(lambda) / (2.0 * std::numbers::pi); };

  // The spectrum on a 2 Hz grid from 100 Hz to 4 kHz; its local maxima above 1 % of the largest
  // and not within 4 / T of a larger one (the Hann window's side lobes, 2.7 % at 2.5 / T), each
  // refined on a 0.05 Hz grid.
  std::vector<double> grid;
  for (double f = 100.0; f <= 4000.0; f += 2.0) grid.push_back(Spectrum(times, along, f));
  const double top = *std::max_element(grid.begin(), grid.end());
  const double lobes = 4.0 / (times.back() - times.front());
  std::vector<std::pair<double, double>> peaks;  // frequency [Hz], amplitude
  for (std::size_t i = 1; i + 1 < grid.size(); ++i) {
    if (!(grid[i] > grid[i - 1] && grid[i] >= grid[i + 1] && grid[i] > 0.01 * top)) continue;
    std::pair<double, double> peak{0.0, 0.0};
    for (double f = 98.0 + 2.0 * i; f <= 102.0 + 2.0 * i; f += 0.05) {
      const double a = Spectrum(times, along, f);
      if (a > peak.second) peak = {f, a};
    }
    peaks.push_back(peak);
  }
  double worst = 0.0;
  int kept = 0;
  for (const std::pair<double, double>& peak : peaks) {
    const double f = peak.first, a = peak.second;  // not a structured binding: clang 14 cannot capture one
    if (std::any_of(peaks.begin(), peaks.end(), [&](const std::pair<double, double>& other) {
          return other.second > a && std::abs(other.first - f) < lobes;
        }))
      continue;
    double nearest = 1e30, nearest_alone = 1e30;
    for (Eigen::Index m = 0; m < K.rows(); ++m) {
      if (std::abs(hz(coupled.eigenvalues()(m)) - f) < std::abs(nearest - f))
        nearest = hz(coupled.eigenvalues()(m));
      if (std::abs(hz(alone.eigenvalues()(m)) - f) < std::abs(nearest_alone - f))
        nearest_alone = hz(alone.eigenvalues()(m));
    }
    ++kept;
    worst = std::max(worst, std::abs(f / nearest - 1.0));
    std::printf(
        "[measured] peak %.2f Hz (%.3g of the largest): beam with the mesh's springs %.2f "
        "Hz (%.2g), nearest of the beam alone %.2f Hz\n",
        f, a / top, nearest, f / nearest - 1.0, nearest_alone);
  }
  EXPECT_GE(kept, 2);
  EXPECT_LT(worst, 2e-4);  // measured 2.2e-5 (the 0.05 Hz grid of 27 Hz wide lines)
}

}  // namespace
}  // namespace flexmbs::mbs
