// The unilateral contacts' Jacobians (mbs/unilateral_contact.h): W_N u is the rate of the gap
// (central differences along the motion) and [W_N; W_T] u the relative velocity of the material
// points at the contact points, for spheres on markers away from their bodies' origins on
// rotating, translating bodies (the [r]x J_w terms), against a moving tilted plane and another
// sphere.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation_error.h"
#include "mbs/unilateral_contact.h"
#include "tests/mbs/rigid_test_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::VectorXd;

using testing::Advance;

TEST(UnilateralContact, JacobiansGiveTheGapRateAndTheMaterialPointsRelativeVelocity) {
  std::mt19937 rng(7);
  MultibodySystem system(Eigen::Vector3d::Zero());
  system.AddBody(testing::RandomRigidBody(rng, "a"));
  system.AddBody(testing::RandomRigidBody(rng, "b"));
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>("plane", system.Marker("a", "m0"),
                                                                       system.Marker("b", "m1"), 0.05,
                                                                       UnilateralLaw{0.5, 0.2}));
  system.AddUnilateralContact(std::make_unique<SphereSphereUnilateral>("spheres", system.Marker("a", "m1"),
                                                                        system.Marker("b", "m0"), 0.05, 0.08,
                                                                        UnilateralLaw{}));
  VectorXd y = system.NeutralState();
  for (int b = 0; b < 2; ++b) {
    VectorXd u(6);
    u << testing::RandomVector(rng, 1.0), testing::RandomVector(rng, 3.0);
    system.SetBodyState(b, testing::RigidPositions(testing::RandomVector(rng, 1.0), testing::RandomRotation(rng)), u, y);
  }
  const VectorXd u = y.tail(system.num_velocities());
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    const UnilateralContact& contact = system.unilateral_contact(k);
    const UnilateralContactKinematics c = contact.Evaluate(0.0, system, y).front();
    // The gap's rate by central differences along the motion (positions moved by +-dt u).
    const double dt = 1e-6;
    const double rate = (contact.Evaluate(0.0, system, Advance(system, y, dt)).front().g_N -
                         contact.Evaluate(0.0, system, Advance(system, y, -dt)).front().g_N) /
                        (2.0 * dt);
    EXPECT_NEAR(c.W_N.dot(u), rate, 1e-8 * (1.0 + std::abs(rate))) << contact.name();
    // The material points' relative velocity from the markers' own velocities.
    const MarkerKinematics a = system.MarkerState(contact.marker_a(), y), b = system.MarkerState(contact.marker_b(), y);
    const Eigen::Vector3d v_rel = a.v_WM_W + a.w_WM_W.cross(c.p_WA_W - a.p_WM_W) -
                                  (b.v_WM_W + b.w_WM_W.cross(c.p_WB_W - b.p_WM_W));
    EXPECT_NEAR(c.W_N.dot(u), c.n_W.dot(v_rel), 1e-13) << contact.name();
    EXPECT_NEAR(c.W_T.row(0).dot(u), c.t1_W.dot(v_rel), 1e-13) << contact.name();
    EXPECT_NEAR(c.W_T.row(1).dot(u), c.t2_W.dot(v_rel), 1e-13) << contact.name();
  }
}

TEST(UnilateralContact, CoincidentCentresStopTheRunNamingTheContactAndTime) {
  MultibodySystem system(Eigen::Vector3d::Zero());
  std::mt19937 rng(3);
  system.AddBody(testing::RandomRigidBody(rng, "a"));
  system.AddUnilateralContact(std::make_unique<SphereSphereUnilateral>(
      "pair", system.Marker("a", "m0"), MarkerRef::Ground(Eigen::Vector3d::Zero()), 0.1, 0.1, UnilateralLaw{}));
  VectorXd y = system.NeutralState();
  const auto& marker = dynamic_cast<const RigidBody&>(system.body(0)).markers()[0];
  system.SetBodyState(0, testing::PoseFromMarker(marker, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()),
                      VectorXd::Zero(6), y);
  try {
    system.unilateral_contact(0).Evaluate(1.5, system, y);
    FAIL() << "no error";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.time(), 1.5);
    EXPECT_NE(std::string(e.what()).find("t = 1.5 s: contact 'pair': sphere-sphere contact: the centres coincide"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace flexmbs::mbs
