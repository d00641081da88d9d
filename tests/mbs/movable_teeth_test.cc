// mbs/movable_teeth_gear_contact: the driven pair of tests/support/driven_gear_pair.h on
// tangentially movable FE teeth, each tooth's deflection a state. The levers against differences
// of the contact search's gaps; held wheels, where one tooth pair's two teeth relax to the static
// series spring along the closed form of their linear equations; the Jacobian blocks against
// central differences; the turning pair's transmission error against the static one of
// contact::StaticTransmissionError; the one-line errors.
#include "mbs/movable_teeth_gear_contact.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/movable_teeth.h"
#include "contact/gears/tooth_stiffness.h"
#include "mbs/multibody_system.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "mbs/spur_gear_contact.h"
#include "mbs/system_jacobian.h"
#include "tests/input_error.h"
#include "tests/mbs/spur_gear_test_pair.h"
#include "tests/support/driven_gear_pair.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using gear_test::GearScene;
using gear_test::kCentre;

constexpr double kLoad = 10.0;  // the wheel's load torque [N m]

/// The driven pair's geometry and FE teeth, as the scene reader builds them (a probe scene with
/// the static elastic teeth).
struct PairAndTeeth {
  contact::GearPair pair;
  contact::ElasticTeeth teeth;
};
PairAndTeeth DrivenPairTeeth(const GearScene& files) {
  const Scene probe = LoadScene(files.Write(flexmbs::testing::DrivenGearPairScene(
      0.0, std::string(flexmbs::testing::kDrivenPairGearKeys) + flexmbs::testing::kDrivenPairFeTeeth)));
  const auto& mesh = dynamic_cast<const SpurGearContact&>(probe.system->force_element(1));
  return {mesh.pair(), *mesh.law().teeth()};
}

/// The pair's wheel angle where its positive flanks touch with the pinion at phi1.
double TouchingAngle(const contact::GearPair& pair, double phi1) {
  return contact::TouchingAngle2(pair, kCentre, phi1, 0.0, contact::FlankSide::kPositive);
}

// PairLevers: turning wheel i by dphi moves every tooth pair's gap by lever_i r_bi dphi. Against
// central differences of MeshingToothPairs' gaps (1e-7 rad) over a mesh period, flanks and tip
// corners. Measured: flanks 1.7e-9, corners 1.3e-8 (the differences' own error; 204 corner pairs).
TEST(MovableTeeth, LeversAreTheGapsDerivativesByEachWheelsTurn) {
  GearScene files;
  const contact::GearPair pair = DrivenPairTeeth(files).pair;
  const double step = 1e-7, period = 2.0 * std::numbers::pi / 19.0;
  double worst_flanks = 0.0, worst_corners = 0.0;
  int corners = 0;
  for (int k = 0; k < 40; ++k) {
    const double phi1 = period * k / 40.0, phi2 = TouchingAngle(pair, phi1) + 2e-4;  // loaded: overlap
    const auto pairs = contact::MeshingToothPairs(pair, kCentre, phi1, phi2);
    const auto gap = [&](double dphi1, double dphi2, const contact::ToothPair& tp) {
      for (const contact::ToothPair& moved : contact::MeshingToothPairs(pair, kCentre, phi1 + dphi1, phi2 + dphi2)) {
        if (moved.side == tp.side && moved.tooth1 == tp.tooth1 && moved.tooth2 == tp.tooth2) return moved.gap;
      }
      ADD_FAILURE() << "pair lost";
      return 0.0;
    };
    for (const contact::ToothPair& tp : pairs) {
      const contact::ToothLevers levers = contact::PairLevers(pair, kCentre, tp);
      const double g1 = (gap(step, 0.0, tp) - gap(-step, 0.0, tp)) / (2.0 * step * pair.gear1.base_radius);
      const double g2 = (gap(0.0, step, tp) - gap(0.0, -step, tp)) / (2.0 * step * pair.gear2.base_radius);
      const double error = std::max(std::abs(g1 - levers.lever1), std::abs(g2 - levers.lever2));
      if (tp.contact == contact::ToothContact::kFlanks) {
        worst_flanks = std::max(worst_flanks, error);
        EXPECT_DOUBLE_EQ(levers.lever1, -contact::Sign(tp.side));
      } else {
        worst_corners = std::max(worst_corners, error);
        ++corners;
      }
    }
  }
  std::printf("levers against differences: flanks %.2e, corners %.2e (%d corner pairs)\n", worst_flanks,
              worst_corners, corners);
  EXPECT_GT(corners, 0);
  EXPECT_LT(worst_flanks, 3e-8);
  EXPECT_LT(worst_corners, 1.3e-7);
}

/// The pair with both wheels held on ground markers, the wheel turned `overlap` [rad] into the
/// pinion past touching at pinion angle phi1: the system's state is the teeth's alone.
struct HeldPair {
  MultibodySystem system{Eigen::Vector3d::Zero()};
  const MovableTeethGearContact* mesh = nullptr;
};
void Hold(HeldPair& held, const PairAndTeeth& gears, double phi1, double overlap, double damping) {
  const auto about_z = [](double angle) { return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix(); };
  const MarkerRef wheel1 = MarkerRef::Ground(Eigen::Vector3d::Zero(), about_z(phi1));
  const MarkerRef wheel2 =
      MarkerRef::Ground(Eigen::Vector3d(kCentre, 0.0, 0.0), about_z(TouchingAngle(gears.pair, phi1) + overlap));
  auto element = std::make_unique<MovableTeethGearContact>("mesh", wheel1, wheel2, gears.pair,
                                                           contact::MovableTeeth{gears.teeth, damping});
  held.mesh = element.get();
  held.system.AddForceElement(std::move(element));
}

// Held wheels in single contact: the loaded pair's teeth d = (d1, d2) follow
//   c_t d' = -(K + k_H l l^T) d + k_H delta_0 l   (K = diag(k_t1, k_t2), l the levers),
// symmetric, so d(t) = d_inf + V exp(-Lambda t / c_t) V^T (d0 - d_inf) exactly; at rest the pair
// carries delta_0 / (1/k_H + 1/k_t1 + 1/k_t2), the static series spring of
// contact::TeethPairStiffness. Measured (implicit, rtol 1e-12): d 1.1e-10 of its final value (9.1e-9
// at rtol 1e-10: the integrator's error), the force at rest 2.6e-13 of the series spring's.
TEST(MovableTeeth, HeldPairRelaxesToTheSeriesSpringAlongTheClosedForm) {
  GearScene files;
  const PairAndTeeth gears = DrivenPairTeeth(files);
  // The middle of the single-contact zone: the pinion angle in a mesh period with one tooth pair
  // penetrating under the overlap, farthest from the angles with two.
  const double overlap = 1e-4, damping = 2e3, period = 2.0 * std::numbers::pi / 19.0;
  std::vector<double> single;
  for (int k = 0; k < 200; ++k) {
    const double angle = period * k / 200.0;
    int penetrating = 0;
    for (const auto& tp : contact::MeshingToothPairs(gears.pair, kCentre, angle, TouchingAngle(gears.pair, angle) + overlap))
      penetrating += tp.gap < 0.0;
    if (penetrating == 1) single.push_back(angle);
  }
  ASSERT_FALSE(single.empty());
  const double phi1 = single[single.size() / 2];
  HeldPair held;
  Hold(held, gears, phi1, overlap, damping);
  const MultibodySystem& system = held.system;
  const VectorXd s0 = system.NeutralState();
  const MovableTeethGearContact::Mesh mesh = held.mesh->Evaluate(0.0, system, s0);
  const MovableTeethGearContact::MovedPair* loaded = nullptr;
  int in_contact = 0;
  for (const auto& p : mesh.pairs) {
    if (p.force > 0.0) {
      loaded = &p;
      ++in_contact;
    }
  }
  ASSERT_EQ(in_contact, 1);
  const VectorXd k_t = held.mesh->ToothStiffnesses(mesh);
  const Eigen::Vector2d lever(loaded->levers.lever1, loaded->levers.lever2);
  const Eigen::Matrix2d A = Eigen::Vector2d(k_t(loaded->state1), k_t(loaded->state2)).asDiagonal().toDenseMatrix() +
                            loaded->stiffness * lever * lever.transpose();
  const double delta0 = loaded->point.penetration;
  const Eigen::Vector2d d_inf = A.ldlt().solve(loaded->stiffness * delta0 * lever);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(A);
  const double series = contact::TeethPairStiffness(gears.teeth, gears.pair, loaded->pair.roll1, loaded->pair.roll2) *
                        gears.pair.gear1.spec.face_width * delta0;

  SimulationOptions options;
  options.end_time = 40.0 * damping / eigen.eigenvalues()(0);  // 40 of the slow time constants
  options.output_interval = options.end_time / 50.0;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = 1e-12;
  options.integrator.absolute_tolerance = 1e-20;
  double worst = 0.0, force_at_rest = 0.0;
  Simulate(held.system, options, s0, [&](double t, const VectorXd& s, const VectorXd&) {
    const Eigen::Vector2d decay = (-eigen.eigenvalues() * t / damping).array().exp();
    const Eigen::Vector2d exact =
        d_inf + eigen.eigenvectors() * decay.asDiagonal() * eigen.eigenvectors().transpose() * (-d_inf);
    const Eigen::Vector2d d(s(loaded->state1), s(loaded->state2));
    worst = std::max(worst, (d - exact).cwiseAbs().maxCoeff() / d_inf.cwiseAbs().maxCoeff());
    force_at_rest = held.mesh->Evaluate(t, held.system, s).pairs[static_cast<std::size_t>(loaded - mesh.pairs.data())].force;
  });
  std::printf("held pair: d against the closed form %.2e; force at rest %.9g N, series spring %.9g N (%.2e)\n",
              worst, force_at_rest, series, force_at_rest / series - 1.0);
  EXPECT_LT(worst, 1.1e-9);
  EXPECT_NEAR(force_at_rest / series, 1.0, 2.6e-12);
}

/// The driven pair (tests/support/driven_gear_pair.h) without its mesh entry, and the movable teeth
/// of its FE tables with tooth damping c_t added as element 2; y0 the scene's with the teeth at rest.
struct TurningPair {
  Scene scene;
  const MovableTeethGearContact* mesh = nullptr;
  VectorXd y0;
};
TurningPair DrivenPairOnMovableTeeth(const GearScene& files, double damping, double end_time) {
  const PairAndTeeth gears = DrivenPairTeeth(files);
  TurningPair turning{LoadScene(files.Write(
                          flexmbs::testing::DrivenGearPairScene(TouchingAngle(gears.pair, 0.0), "", end_time))),
                      nullptr, VectorXd()};
  MultibodySystem& system = *turning.scene.system;
  auto element = std::make_unique<MovableTeethGearContact>("mesh", system.Marker("pinion", "axis"),
                                                           system.Marker("wheel", "axis"), gears.pair,
                                                           contact::MovableTeeth{gears.teeth, damping});
  turning.mesh = element.get();
  system.AddForceElement(std::move(element));
  turning.y0 = VectorXd::Zero(system.state_size());
  turning.y0.head(turning.scene.initial_state.size()) = turning.scene.initial_state;
  return turning;
}

// The element's state blocks against central differences at a loaded state in double contact with
// the teeth deflected: ds'/ds and dh/ds exactly (linear in d inside the contact set), ds'/dx by the
// wheels' turns up to the levers', k_H's and k_t's change with the angles (left out). Measured:
// ds'/ds 3.8e-13, dh/ds 9.1e-13 relative to their largest entries, ds'/dx 2.3e-4.
TEST(MovableTeeth, StateJacobianBlocksMatchDifferences) {
  GearScene files;
  TurningPair turning = DrivenPairOnMovableTeeth(files, 2e3, 0.1);
  const MultibodySystem& system = *turning.scene.system;
  const Index nx = system.num_positions(), nu = system.num_velocities(), ns = system.num_element_states();
  // Find a double contact: turn the wheel into the pinion until two pairs penetrate, then deflect
  // the loaded teeth part of the way.
  VectorXd y = turning.y0;
  const int wheel = system.FindBody("wheel");
  for (double phi1 = 0.0;; phi1 += 0.002) {
    VectorXd trial = turning.y0;
    VectorXd turn = VectorXd::Zero(nu);
    turn(system.velocity_offset(system.FindBody("pinion")) + 5) = phi1;
    turn(system.velocity_offset(wheel) + 5) = -phi1 * 19.0 / 31.0 + 1e-4;
    system.DisplacePositions(turn, trial);
    int loaded = 0;
    for (const auto& p : turning.mesh->Evaluate(0.0, system, trial).pairs) loaded += p.force > 0.0;
    if (loaded == 2) {
      y = trial;
      break;
    }
    ASSERT_LT(phi1, 0.4);
  }
  for (const auto& p : turning.mesh->Evaluate(0.0, system, y).pairs) {
    if (p.force <= 0.0) continue;
    y(system.element_state_offset(1) + p.state1) = 0.3 * p.levers.lever1 * p.force / 1.5e9;
    y(system.element_state_offset(1) + p.state2) = 0.3 * p.levers.lever2 * p.force / 1.5e9;
  }
  MatrixXd ds_dx = MatrixXd::Zero(ns, nu), ds_du = MatrixXd::Zero(ns, nu), ds_ds = MatrixXd::Zero(ns, ns),
           dh_ds = MatrixXd::Zero(nu, ns);
  ElementStateJacobian blocks{ds_dx, ds_du, ds_ds, dh_ds};
  turning.mesh->AddStateJacobian(0.0, system, y, blocks);

  const auto rates = [&](const VectorXd& at) {
    VectorXd s_dot(ns);
    turning.mesh->StateDerivatives(0.0, system, at, s_dot);
    return s_dot;
  };
  const auto forces = [&](const VectorXd& at) {
    VectorXd h = VectorXd::Zero(nu);
    turning.mesh->AddForces(0.0, system, at, h);
    return h;
  };
  MatrixXd ds_ds_diff(ns, ns), dh_ds_diff(nu, ns), ds_dx_diff(ns, nu);
  const double dd = 1e-10;  // [m] against deflections of ~1e-7
  for (Index j = 0; j < ns; ++j) {
    VectorXd plus = y, minus = y;
    plus(nx + nu + j) += dd;
    minus(nx + nu + j) -= dd;
    ds_ds_diff.col(j) = (rates(plus) - rates(minus)) / (2.0 * dd);
    dh_ds_diff.col(j) = (forces(plus) - forces(minus)) / (2.0 * dd);
  }
  const double dtheta = 1e-9;  // [rad, m]
  for (Index j = 0; j < nu; ++j) {
    VectorXd plus = y, minus = y, step = VectorXd::Zero(nu);
    step(j) = dtheta;
    system.DisplacePositions(step, plus);
    system.DisplacePositions(-step, minus);
    ds_dx_diff.col(j) = (rates(plus) - rates(minus)) / (2.0 * dtheta);
  }
  const auto relative = [](const MatrixXd& model, const MatrixXd& difference) {
    return (model - difference).cwiseAbs().maxCoeff() / difference.cwiseAbs().maxCoeff();
  };
  std::printf("state blocks against differences: ds'/ds %.2e, dh/ds %.2e, ds'/dx %.2e; ds'/du %.3g\n",
              relative(ds_ds, ds_ds_diff), relative(dh_ds, dh_ds_diff), relative(ds_dx, ds_dx_diff),
              ds_du.cwiseAbs().maxCoeff());
  EXPECT_LT(relative(ds_ds, ds_ds_diff), 4e-12);
  EXPECT_LT(relative(dh_ds, dh_ds_diff), 9e-12);
  EXPECT_LT(relative(ds_dx, ds_dx_diff), 2.3e-3);
}

// The pinion turns at 2 rad/s against 10 N m on the wheel, the teeth's dashpots at c_t = 2e4 N s/m
// (a tooth's time constant c_t / k_t ~ 1.5e-5 s, 1e-4 of the mesh period): the wheel's lag along
// the line of action, r_b2 (phi2 - phi2_0(phi1)), follows the static transmission error of the same
// teeth (contact::StaticTransmissionError with MeshLaw's quasi-static series, other code) over a
// mesh period. Measured: 2.8e-9 m of the largest 1.0e-6 m (0.28 %; 2458 implicit steps, 1.8 s).
// The dashpots' lag grows with c_t: 2.9e-9 / 2.8e-9 / 1.1e-8 / 3.2e-8 m at c_t = 5e3 / 2e4 / 8e4 /
// 3.2e5 N s/m; the floor is the wheels' own ringing at the load's switches.
TEST(MovableTeeth, TurningPairFollowsTheStaticTransmissionError) {
  GearScene files;
  const double mesh_period = 2.0 * std::numbers::pi / 19.0 / 2.0, t0 = 0.05, t1 = t0 + mesh_period;
  TurningPair turning = DrivenPairOnMovableTeeth(files, 2e4, t1);
  MultibodySystem& system = *turning.scene.system;
  SimulationOptions options = turning.scene.options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.max_step = 0.0;
  options.integrator.relative_tolerance = 1e-8;
  options.output_interval = 5e-4;
  const contact::GearPair& pair = turning.mesh->pair();
  const contact::MeshLaw law(pair, turning.mesh->teeth().teeth, 0.0);
  const double torque1 = kLoad * pair.gear1.base_radius / pair.gear2.base_radius;
  double worst = 0.0, largest = 0.0;
  int samples = 0;
  const SimulationStatistics statistics = Simulate(system, options, turning.y0, [&](double t, const VectorXd& y, const VectorXd&) {
    if (t < t0) return;
    const GearPairFrame f = turning.mesh->Evaluate(t, system, y).frame;
    const double lag = pair.gear2.base_radius *
                       std::remainder(f.phi2 - contact::TouchingAngle2(pair, kCentre, f.phi1, f.phi2, contact::FlankSide::kPositive),
                                      2.0 * std::numbers::pi);
    const double ste = contact::StaticTransmissionError(pair, law, kCentre, f.phi1, torque1);
    worst = std::max(worst, std::abs(lag - ste));
    largest = std::max(largest, ste);
    ++samples;
  });
  std::printf("turning pair on movable teeth: lag against the static transmission error %.3e m of %.3e m "
              "(%d samples, %ld steps, %ld Newton iterations)\n",
              worst, largest, samples, statistics.integrator.steps, statistics.integrator.newton_iterations);
  EXPECT_GT(samples, 300);
  EXPECT_LT(worst, 2.8e-8);
}

/// The driven pair's scene with its FE teeth movable (docs/scene.md's entry), `extra` appended to
/// the `movable` map's line and `pair_damping` (none where empty) as the entry's per-pair damping.
std::string MovableScene(const std::string& movable, const std::string& pair_damping = "") {
  std::string keys =
      "    gear1: {module: 2e-3, teeth: 19, profile_shift: 0.3, face_width: 0.02}\n"
      "    gear2: {module: 2e-3, teeth: 31, profile_shift: -0.1, face_width: 0.02}\n"
      "    centre_distance: 0.0505\n";
  if (!pair_damping.empty()) keys += "    damping: " + pair_damping + "\n";
  keys += std::string(flexmbs::testing::kDrivenPairFeTeeth) + "      movable: " + movable + "\n";
  return flexmbs::testing::DrivenGearPairScene(0.0, keys, 0.01);
}

// The scene's `teeth: movable: {damping}` builds the element with a state per tooth, and the
// run's deflections are the states.
TEST(MovableTeeth, SceneEntryBuildsTheElementWithAStatePerTooth) {
  GearScene files;
  const Scene scene = LoadScene(files.Write(MovableScene("{damping: 2e4}")));
  const auto* mesh = dynamic_cast<const MovableTeethGearContact*>(&scene.system->force_element(1));
  ASSERT_NE(mesh, nullptr);
  EXPECT_EQ(scene.system->num_element_states(), 19 + 31);
  EXPECT_EQ(scene.initial_state.size(), scene.system->state_size());
  EXPECT_EQ(mesh->teeth().damping, 2e4);
}

// Bad movable entries are one-line errors at their item.
TEST(MovableTeeth, BadSceneEntriesAreOneLineErrors) {
  GearScene files;
  const auto message = [&](const std::string& text) {
    return flexmbs::testing::InputErrorMessage([&] { LoadScene(files.Write(text)); });
  };
  const std::string zero = message(MovableScene("{damping: 0}"));
  EXPECT_NE(zero.find("force element 'mesh': movable teeth: tooth damping 0 N s/m must be finite and > 0"),
            std::string::npos)
      << zero;
  const std::string both = message(MovableScene("{damping: 2e4}", "8e3"));
  EXPECT_NE(both.find("damping: force element 'mesh': movable teeth take their damping per tooth"), std::string::npos)
      << both;
  const std::string unknown = message(MovableScene("{damping: 2e4, mass: 1}"));
  EXPECT_NE(unknown.find("mass"), std::string::npos) << unknown;
  const std::string missing = message(MovableScene("{}"));
  EXPECT_NE(missing.find("damping"), std::string::npos) << missing;
  std::printf("%s\n%s\n%s\n%s\n", zero.c_str(), both.c_str(), unknown.c_str(), missing.c_str());
}

}  // namespace
}  // namespace flexmbs::mbs
