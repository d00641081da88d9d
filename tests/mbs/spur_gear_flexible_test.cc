// mbs/spur_gear_contact on a flexible body: the wheel sits on the tip interface of a clamped
// Craig-Bampton beam, the pinion on a revolute joint turns slowly into it. At rest the pinion's
// turn along the line of action is shared by the mesh (F / (c' b n)) and the beam's tip, whose
// compliance along the line through the contact point comes from the FE model's stiffness
// condensed to the tip (the constraint modes, Phi_c^T K Phi_c): the mesh force reaches the
// body's modes as a load on the tip with its lever.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/spur_gear_contact.h"
#include "mbs/time_function.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;

TEST(SpurGearOnFlexibleBody, PinionTurnIsSharedByTheMeshAndTheBeamsTipCompliance) {
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(std::make_unique<FlexibleBody>("beam", fe.body, false));
  system.AddJoint(Joint("clamp", JointType::kFixed, MarkerRef::Ground(Vector3d::Zero()),
                        system.Marker("beam", FlexibleBody::kOriginMarker)));
  const MarkerRef tip = system.Marker("beam", "tip");
  const Vector3d p_tip = system.MarkerState(tip, system.NeutralState()).p_WM_W;

  contact::GearPairSpec spec;
  spec.gear1 =
      contact::SpurGearSpec{2e-3, 19, 20.0 * std::numbers::pi / 180.0, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 =
      contact::SpurGearSpec{2e-3, 31, 20.0 * std::numbers::pi / 180.0, -0.1, 1.0, 1.25, 0.02};
  spec.centre_distance = 0.0505;
  const contact::GearPair pair = contact::MakeGearPair(spec);
  const Vector3d p_pinion = p_tip - Vector3d(0.0505, 0.0, 0.0);  // line of centres along +x
  system.AddBody(std::make_unique<RigidBody>(
      "pinion", 0.18, Vector3d::Zero(),
      Eigen::Vector3d(2e-5, 2e-5, 3.4e-5).asDiagonal().toDenseMatrix(),
      std::vector<RigidBodyMarker>{{"axis", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  // Wheel 1's touching angle with the wheel at 0 (dg/dphi1 = -r_b1 on the positive flanks), then a
  // quintic turn of 2e-3 rad into the mesh over 0.2 s, held to 0.35 s.
  const double touch = contact::SmallestGap(contact::MeshingToothPairs(pair, 0.0505, 0.0, 0.0),
                                            contact::FlankSide::kPositive) /
                       pair.gear1.base_radius;
  const double turn = 2e-3;
  system.AddJoint(Joint("pinion_axis", JointType::kRevolute, MarkerRef::Ground(p_pinion),
                        system.Marker("pinion", "axis"),
                        MakeSmoothStep(0.0, touch, 0.2, touch + turn, SmoothStepOrder::kQuintic)));
  const double k = 1.4e10 * 0.02;
  system.AddForceElement(
      std::make_unique<SpurGearContact>("mesh", system.Marker("pinion", "axis"), tip, pair,
                                        contact::ToothPairLaw({1.4e10, 0.0}, pair)));
  Eigen::VectorXd y0 = system.NeutralState();
  Eigen::VectorXd x(7), u = Eigen::VectorXd::Zero(6);
  x << p_pinion, std::cos(touch / 2), 0.0, 0.0, std::sin(touch / 2);
  system.SetBodyState(1, x, u, y0);

  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = 1e-8;
  options.integrator.absolute_tolerance = 1e-12;
  options.end_time = 0.35;
  options.output_interval = 0.35;
  Eigen::VectorXd y_end;
  Simulate(system, options, y0,
           [&](double, const Eigen::VectorXd& y, const Eigen::VectorXd&) { y_end = y; });

  const auto& mesh = dynamic_cast<const SpurGearContact&>(system.force_element(0));
  const std::vector<ContactLoad> loads = mesh.ContactLoads(0.35, system, y_end);
  ASSERT_FALSE(loads.empty());
  double force = 0.0;
  for (const ContactLoad& load : loads) force += load.f_W.norm();
  const Vector3d n = loads.front().n_W, p_c = loads.front().p_W;

  // The tip's static compliance from the FE model: the stiffness condensed to the tip's six
  // interface coordinates (translations, rotations about the tip node) by its constraint modes.
  std::vector<Eigen::Index> columns;
  for (const char* name : {"constraint_tip_tx", "constraint_tip_ty", "constraint_tip_tz",
                           "constraint_tip_rx", "constraint_tip_ry", "constraint_tip_rz"}) {
    const auto at = std::find(fe.basis.names.begin(), fe.basis.names.end(), name);
    ASSERT_NE(at, fe.basis.names.end()) << name;
    columns.push_back(at - fe.basis.names.begin());
  }
  const Eigen::MatrixXd Phi_c = fe.basis.Phi(Eigen::all, columns);
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

}  // namespace
}  // namespace flexmbs::mbs
