// mbs/spur_gear_contact: two rigid wheels on revolute joints meshing through a spur_gear_contact
// scene entry, the pinion driven at constant speed against a load torque on the wheel: the
// transmission ratio holds and the mesh force carries T / r_b2; the entry's one-line errors.
#include "mbs/spur_gear_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/tooth_stiffness.h"
#include "mbs/multibody_system.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "mbs/simulation_error.h"
#include "tests/input_error.h"
#include "tests/mbs/spur_gear_test_pair.h"
#include "tests/support/driven_gear_pair.h"

namespace flexmbs::mbs {
namespace {

using gear_test::AddFreeWheelsInMesh;
using gear_test::DoubleContactState;
using gear_test::GearScene;
using gear_test::JacobianErrors;
using gear_test::kCentre;

constexpr double kSpeed = 2.0;      // pinion [rad/s]
constexpr double kTorque = 10.0;    // load on the wheel [N m], against its turning

/// The shared driven pair (tests/support/driven_gear_pair.h) with the mesh keys `gear_keys`.
std::string SceneText(double wheel_angle, const std::string& gear_keys) {
  return flexmbs::testing::DrivenGearPairScene(wheel_angle, gear_keys);
}

const char* const kGearKeys = flexmbs::testing::kDrivenPairGearKeys;

/// The angle of a body's z rotation from its rotation matrix [rad], in (-pi, pi].
double AngleAboutZ(const MarkerKinematics& m) { return std::atan2(m.R_WM(1, 0), m.R_WM(0, 0)); }

/// The difference b - a brought into (-pi, pi].
double Unwrapped(double a, double b) { return std::remainder(b - a, 2.0 * std::numbers::pi); }

/// The wheel's angle where its teeth touch the pinion's on the driving flanks (contact/gears).
double StartAngle(const GearScene& files) {
  const Scene probe = LoadScene(files.Write(SceneText(0.0, kGearKeys)));
  const auto& mesh = dynamic_cast<const SpurGearContact&>(probe.system->force_element(1));
  return contact::TouchingAngle2(mesh.pair(), kCentre, 0.0, 0.0, contact::FlankSide::kPositive);
}

// On the line of action alone (tip_corners: false), the textbook's rigid path of contact.
TEST(SpurGearContact, DrivenPairKeepsTheRatioAndCarriesTheLoadTorqueOverTheBaseRadius) {
  GearScene files;
  const Scene scene = LoadScene(
      files.Write(SceneText(StartAngle(files), std::string(kGearKeys) + "    tip_corners: false\n")));
  MultibodySystem& system = *scene.system;
  const auto& gears = dynamic_cast<const SpurGearContact&>(system.force_element(1));
  const double r_b2 = gears.pair().gear2.base_radius;
  const MarkerRef pinion = MarkerRef::OnBody(system.FindBody("pinion"), 0);
  const MarkerRef wheel = MarkerRef::OnBody(system.FindBody("wheel"), 0);

  // From 0.2 s (the start's transient long gone) over 5 whole mesh cycles of the pinion. Where a
  // tooth pair enters or leaves, the mesh stiffness steps (1 <-> 2 pairs) and the wheel rings at
  // the mesh's natural frequency (5 kHz, damping ratio ~0.5); kSettled after that the force is
  // back at T / r_b2.
  constexpr double kSettled = 1e-3;
  const double mesh_period = 2.0 * std::numbers::pi / 19.0 / kSpeed;
  const double t0 = 0.2, t1 = t0 + 5.0 * mesh_period;
  double phi1 = 0.0, phi2 = 0.0, turned1 = 0.0, turned2 = 0.0, impulse = 0.0, last_t = -1.0,
         last_force = 0.0;
  double worst_force = 0.0, last_switch = 0.0;
  int samples = 0, last_touching = 0;
  Simulate(system, scene.options, scene.initial_state,
           [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
             const double a1 = AngleAboutZ(system.MarkerState(pinion, y)),
                          a2 = AngleAboutZ(system.MarkerState(wheel, y));
             const double force = gears.MeshForce(t, system, y);
             int touching = 0;
             for (const contact::ToothPair& tp : gears.ToothPairs(t, system, y))
               touching += tp.gap < 0.0;
             if (touching != last_touching) last_switch = t;
             last_touching = touching;
             if (t > t0 - 1e-9 && t < t1 + 1e-9) {
               if (last_t >= 0.0) {
                 turned1 += Unwrapped(phi1, a1);
                 turned2 += Unwrapped(phi2, a2);
                 impulse += 0.5 * (force + last_force) * (t - last_t);
               }
               if (t - last_switch > kSettled)
                 worst_force = std::max(worst_force, std::abs(force * r_b2 / kTorque - 1.0));
               last_t = t;
               last_force = force;
               ++samples;
             }
             phi1 = a1;
             phi2 = a2;
           });
  ASSERT_GT(samples, 1000);
  const double ratio = turned2 / turned1;
  const double mean_force = impulse / (t1 - t0);
  std::printf(
      "[measured] ratio %.12f against -19/31 = %.12f; mean mesh force %.6f N against T/r_b2 = %.6f "
      "N; "
      "largest deviation %.3g ms after a switch %.3g\n",
      ratio, -19.0 / 31.0, mean_force, kTorque / r_b2, kSettled * 1e3, worst_force);
  EXPECT_NEAR(ratio, -19.0 / 31.0, 2e-11);  // measured 2.3e-12 (the end points' deflections differ)
  // The trapezoid over 1e-4 s outputs misses part of the 5 kHz ringing's spikes: measured 1.7e-4.
  EXPECT_NEAR(mean_force * r_b2 / kTorque, 1.0, 1e-3);
  EXPECT_LT(worst_force, 1e-5);  // measured 9.1e-7 (the integrator's tolerance)
}

/// The wheel's mesh torque against the load over five mesh cycles from 0.2 s of the driven pair
/// with `gear_keys`: the largest and the root mean square of |T_mesh / T - 1| (T_mesh the
/// element's torque on the wheel about its axis, from SpurGearContact::Read), and the share of
/// the time with two or more tooth pairs loaded.
struct MeshTorqueRipple {
  double largest = 0.0, rms = 0.0, loaded_twice = 0.0;
};
MeshTorqueRipple RunDrivenPair(const std::string& gear_keys) {
  GearScene files;
  const double mesh_period = 2.0 * std::numbers::pi / 19.0 / kSpeed;
  const double t0 = 0.2, t1 = t0 + 5.0 * mesh_period;
  const Scene scene = LoadScene(files.Write(
      flexmbs::testing::DrivenGearPairScene(StartAngle(files), gear_keys, t1 + 1e-3)));
  MultibodySystem& system = *scene.system;
  const auto& gears = dynamic_cast<const SpurGearContact&>(system.force_element(1));
  MeshTorqueRipple ripple;
  int samples = 0;
  Simulate(system, scene.options, scene.initial_state,
           [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
             if (t < t0 - 1e-9 || t > t1 + 1e-9) return;
             const SpurGearContact::Readout mesh = gears.Read(t, system, y);
             const double deviation = std::abs(-mesh.torque2 / kTorque - 1.0);
             ripple.largest = std::max(ripple.largest, deviation);
             ripple.rms += deviation * deviation;
             int loaded = 0;
             for (const contact::ToothPairLoad& load : mesh.pairs) loaded += load.force > 0.0;
             ripple.loaded_twice += loaded >= 2;
             ++samples;
           });
  EXPECT_GT(samples, 400);
  ripple.rms = std::sqrt(ripple.rms / samples);
  ripple.loaded_twice /= samples;
  return ripple;
}

// Without its tip corners, a tooth pair enters the loaded mesh with the full deflection of the
// pair already in it: the mesh stiffness steps and the wheel rings (5 kHz, damped within 1 ms)
// at every switch. With them, wheel 2's corner meets wheel 1's flank before the path of contact
// and takes load gradually (the force grows with the corner's overlap from zero), and wheel 1's
// leaves gradually after it: the mesh torque's ripple about the load shrinks.
TEST(SpurGearContact, TipCornersTakeTheLoadOverGraduallyAndTheMeshRingsLess) {
  const MeshTorqueRipple line = RunDrivenPair(std::string(kGearKeys) + "    tip_corners: false\n");
  const MeshTorqueRipple corners = RunDrivenPair(kGearKeys);
  std::printf(
      "[measured] mesh torque against the load over 5 mesh cycles: largest deviation %.3g (line "
      "of action alone) -> %.3g (tip corners), rms %.3g -> %.3g; two or more pairs loaded %.4f "
      "-> %.4f of the time\n",
      line.largest, corners.largest, line.rms, corners.rms, line.loaded_twice,
      corners.loaded_twice);
  // Measured 0.464 -> 0.00488 (0.0105 of it) and 0.0083 -> 9.96e-5 (0.012); 0.4765 -> 0.5285.
  EXPECT_LT(corners.largest, 0.05 * line.largest);
  EXPECT_LT(corners.rms, 0.05 * line.rms);
  EXPECT_GT(corners.loaded_twice, line.loaded_twice + 0.02);
}

/// Each pair's load on the wheel lies along its line of action, as ParaView draws them, and
/// the two sum to the mesh force.
void ExpectLoadsAlongTheLinesOfAction(const MultibodySystem& system, const ForceElement& mesh,
                                      const Eigen::VectorXd& y) {
  const auto loads = mesh.ContactLoads(0.0, system, y);
  ASSERT_EQ(loads.size(), 2u);
  EXPECT_TRUE(mesh.is_contact());
  double total = 0.0;
  for (const ContactLoad& load : loads) {
    EXPECT_LT((load.f_W - load.f_W.norm() * load.n_W).norm(), 1e-12 * load.f_W.norm());
    total += load.f_W.norm();
  }
  EXPECT_NEAR(total, dynamic_cast<const SpurGearContact&>(mesh).MeshForce(0.0, system, y),
              1e-12 * total);
}

// The element's Jacobian against central differences of its forces, two free wheels turning
// with both tooth pairs in contact 5 um deep: in u exact (the dashpot on the relative velocity at
// each contact point); in x for the wheels' turns about their axes (the columns the mesh's
// stiffness lives in: the contact points slide along the line of action, parallel to the force,
// so the levers add nothing). Left out: the line of action's turning when a centre moves.
TEST(SpurGearContact, JacobianIsTheForcesDerivativeForTurnsAndVelocities) {
  MultibodySystem system(Eigen::Vector3d::Zero());
  const contact::GearPair pair = AddFreeWheelsInMesh(system);
  const Eigen::VectorXd y = DoubleContactState(system, pair);
  const ForceElement& mesh = system.force_element(0);
  int penetrating = 0;
  for (const contact::ToothPair& tp :
       dynamic_cast<const SpurGearContact&>(mesh).ToothPairs(0.0, system, y)) {
    penetrating += tp.gap < 0.0;
  }
  ASSERT_EQ(penetrating, 2);
  ExpectLoadsAlongTheLinesOfAction(system, mesh, y);
  const auto [error_u, error_x] = JacobianErrors(system, mesh, y);
  std::printf("[measured] spur gear Jacobian: u %.2g, x (turns) %.2g of the largest entry\n",
              error_u, error_x);
  EXPECT_LT(error_u, 6e-10);  // measured 5.8e-11
  EXPECT_LT(error_x, 7e-8);   // measured 7.1e-9: the quaternion's round-off over steps of 1e-8 rad
}

// With wheel 2's tip corner 2 um into wheel 1's flank before the path of contact (and a pair on
// the line), the same comparison: the corner's normal is wheel 1's flank's at the foot, which
// turns as the foot slides along the flank; the Jacobian leaves that turning out (F dn, of the
// order of F r against the stiffness' c' b r^2).
TEST(SpurGearContact, JacobianWithATipCornerInContactLeavesOutOnlyTheNormalsTurning) {
  MultibodySystem system(Eigen::Vector3d::Zero());
  const contact::GearPair pair = AddFreeWheelsInMesh(system);
  const ForceElement& mesh = system.force_element(0);
  Eigen::VectorXd y;
  double corner_gap = 0.0;
  for (double phi1 = 0.3; phi1 < 0.7 && !(corner_gap < -2e-6); phi1 += 1e-4) {
    y = DoubleContactState(system, pair, phi1, 1e-5);
    corner_gap = 0.0;
    for (const contact::ToothPair& tp :
         dynamic_cast<const SpurGearContact&>(mesh).ToothPairs(0.0, system, y)) {
      if (tp.contact == contact::ToothContact::kTip2OnFlank1)
        corner_gap = std::min(corner_gap, tp.gap);
    }
  }
  ASSERT_LT(corner_gap, -2e-6);
  const auto [error_u, error_x] = JacobianErrors(system, mesh, y);
  std::printf(
      "[measured] spur gear Jacobian with a tip corner %.3g m deep: u %.2g, x (turns) %.2g of the "
      "largest entry\n",
      corner_gap, error_u, error_x);
  EXPECT_LT(error_u, 6e-10);  // measured 4.9e-11
  EXPECT_LT(error_x, 1e-3);   // measured 1.7e-4 (F dn; the line's pairs alone gave 7.1e-9)
}

// A wheel marker whose z axis points the other way (the wheels' angles would count in opposite
// senses) stops the run with the time and the angle between the axes.
TEST(SpurGearContact, ReversedWheelAxisStopsTheRun) {
  GearScene files;
  std::string text = SceneText(0.0, kGearKeys);
  const std::string markers = "    markers: {axis: {position: [0, 0, 0]}}\n";
  const std::size_t wheel = text.find(markers, text.find("  wheel:"));
  text.replace(wheel, markers.size(),
               "    markers: {axis: {position: [0, 0, 0]}, flipped: {position: [0, 0, 0], "
               "rotation: {axis: [1, 0, 0], "
               "angle: 3.141592653589793}}}\n");
  const std::string key = "wheel2: {body: wheel, marker: axis}";
  text.replace(text.find(key), key.size(), "wheel2: {body: wheel, marker: flipped}");
  const Scene scene = LoadScene(files.Write(text));
  try {
    Simulate(*scene.system, scene.options, scene.initial_state,
             [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {});
    ADD_FAILURE() << "no error";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "spur gear contact 'mesh': the wheels' axes (the markers' z) are 180 deg apart"),
              std::string::npos)
        << e.what();
  }
}

TEST(SpurGearContact, BadGearEntriesAreOneLineErrorsAtTheirItem) {
  GearScene files;
  const auto refused = [&](const std::string& keys) {
    return flexmbs::testing::InputErrorMessage(
        [&] { LoadScene(files.Write(SceneText(0.0, keys))); });
  };
  std::string message = refused(
      "    gear1: {module: 2e-3, teeth: 12, face_width: 0.02}\n"
      "    gear2: {module: 2e-3, teeth: 31, face_width: 0.02}\n");
  EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("force element 'mesh': gear 1: teeth 12 < z_min"), std::string::npos)
      << message;
  message = refused(
      "    gear1: {module: 2e-3, teeth: 19, face_width: 0.02}\n"
      "    gear2: {module: 3e-3, teeth: 31, face_width: 0.02}\n");
  EXPECT_NE(
      message.find(
          "force element 'mesh': gears cannot mesh: module 0.002 m of gear 1 differs from 0.003 m"),
      std::string::npos)
      << message;
  message = refused(std::string(kGearKeys) + "    mesh_stiffness: -1\n");
  EXPECT_NE(
      message.find("force element 'mesh': mesh stiffness c' [N/m^2] -1 must be finite and > 0"),
      std::string::npos)
      << message;
  message = refused(std::string(kGearKeys) + "    teeth: 3\n");
  EXPECT_NE(message.find("teeth"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  const std::string table =
      "{roll: [0.2, 0.5], compliance: [1e-11, 3e-11], centre_depth: [2e-3, 1e-3]}";
  message =
      refused(std::string(kGearKeys) + "    mesh_stiffness: 1.4e10\n    teeth: {gear1: " + table +
              ", gear2: " + table + "}\n");
  EXPECT_NE(message.find("forces[1].mesh_stiffness: give either mesh_stiffness or teeth, not both"),
            std::string::npos)
      << message;
  message = refused(std::string(kGearKeys) +
                    "    teeth: {gear1: {roll: [0.5, 0.2], compliance: [1e-11, 3e-11], "
                    "centre_depth: [2e-3, 1e-3]}, gear2: " +
                    table + "}\n");
  EXPECT_NE(message.find("force element 'mesh': gear 1 tooth: roll[1] 0.2 rad must be finite, > 0 "
                         "and above roll[0]"),
            std::string::npos)
      << message;
  // The pair with gear 2's tip relief as given.
  const auto with_relief = [](const std::string& relief) {
    return "    gear1: {module: 2e-3, teeth: 19, profile_shift: 0.3, face_width: 0.02}\n"
           "    gear2: {module: 2e-3, teeth: 31, profile_shift: -0.1, face_width: 0.02,\n"
           "            tip_relief: " + relief + "}\n";
  };
  message = refused(with_relief("{amount: 2e-5, length: 1e-3, shape: cubic}"));
  EXPECT_NE(message.find("forces[1].gear2.tip_relief.shape: 'cubic' must be one of: linear, "
                         "parabolic"),
            std::string::npos)
      << message;
  message = refused(with_relief("{amount: -2e-5, length: 1e-3}"));
  EXPECT_NE(message.find("force element 'mesh': gear 2: tip relief C_a [m] -2e-05 must be finite "
                         "and >= 0"),
            std::string::npos)
      << message;
  message = refused(std::string(kGearKeys) + "    teeth: {gear1: " + table + ", gear2: " + table +
                    ", poisson_ratio: 0.5}\n");
  EXPECT_NE(message.find("force element 'mesh': Poisson's ratio 0.5 must be in [0, 0.5)"),
            std::string::npos)
      << message;
  message = refused(std::string(kGearKeys) +
                    "    teeth: {gear1: {roll: [0.2, 0.5]}, gear2: " + table + "}\n");
  EXPECT_NE(message.find("teeth.gear1"), std::string::npos) << message;
  EXPECT_NE(message.find("compliance"), std::string::npos) << message;
}

// `mesh_stiffness: iso` takes ISO 6336-1's c' of the pair (contact::IsoSinglePairStiffness, its
// own test in tests/contact/gear_teeth_test.cc) for every tooth pair, times the face width.
TEST(SpurGearContact, IsoMeshStiffnessIsTheStandardsSinglePairStiffness) {
  GearScene files;
  const Scene scene =
      LoadScene(files.Write(SceneText(0.0, std::string(kGearKeys) + "    mesh_stiffness: iso\n")));
  const auto& mesh = dynamic_cast<const SpurGearContact&>(scene.system->force_element(1));
  const contact::IsoMeshStiffness iso =
      contact::IsoSinglePairStiffness(mesh.pair().gear1.spec, mesh.pair().gear2.spec);
  const contact::ToothPair any;
  EXPECT_DOUBLE_EQ(mesh.law().PairLaw(any).stiffness, iso.single_pair * 0.02);
  EXPECT_FALSE(mesh.law().elastic());
}

// A wheel's `tip_relief` reaches the pair's wheels (contact/gears' TipRelief; its effect on the
// mesh is tests/contact/gear_mesh_test.cc's): amount, length and the parabolic shape.
TEST(SpurGearContact, TipReliefEntryReachesTheWheel) {
  GearScene files;
  const Scene scene = LoadScene(files.Write(SceneText(
      0.0,
      "    gear1: {module: 2e-3, teeth: 19, profile_shift: 0.3, face_width: 0.02}\n"
      "    gear2: {module: 2e-3, teeth: 31, profile_shift: -0.1, face_width: 0.02,\n"
      "            tip_relief: {amount: 2e-5, length: 1e-3, shape: parabolic}}\n"
      "    centre_distance: 0.0505\n")));
  const auto& mesh = dynamic_cast<const SpurGearContact&>(scene.system->force_element(1));
  EXPECT_EQ(mesh.pair().gear1.spec.tip_relief, 0.0);
  EXPECT_EQ(mesh.pair().gear2.spec.tip_relief, 2e-5);
  EXPECT_EQ(mesh.pair().gear2.spec.tip_relief_length, 1e-3);
  EXPECT_EQ(mesh.pair().gear2.spec.tip_relief_exponent, 2);
}

// tip_corners: on by default, off when the entry says false; anything but a boolean is refused
// in one line at the key.
TEST(SpurGearContact, TipCornersEntryReachesThePairAndRefusesANonBoolean) {
  GearScene files;
  const auto pair = [&](const std::string& keys) {
    const Scene scene = LoadScene(files.Write(SceneText(0.0, keys)));
    return dynamic_cast<const SpurGearContact&>(scene.system->force_element(1)).pair();
  };
  EXPECT_TRUE(pair(kGearKeys).tip_corners);
  EXPECT_FALSE(pair(std::string(kGearKeys) + "    tip_corners: false\n").tip_corners);
  const std::string message = flexmbs::testing::InputErrorMessage([&] {
    LoadScene(files.Write(SceneText(0.0, std::string(kGearKeys) + "    tip_corners: maybe\n")));
  });
  EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("tip_corners"), std::string::npos) << message;
  EXPECT_NE(message.find("'maybe' is not true or false"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs
