// Contacts on a reduced body's contact surface (mbs/surface_unilateral.h,
// mbs/surface_contact_force.h) on a moving, rotating, deforming free-free beam: W_N u is the rate
// of every point's gap (central differences along the motion, modal coordinates included); the
// compliant sphere-surface element's generalised force does the work f . v_rel (its modal rows
// included) and its Jacobian in u matches difference quotients of its forces; the compliant
// surface-on-plane element loads each penetrating vertex by W_N^T F_N.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <random>
#include <vector>

#include "contact/laws/normal_law.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/surface_contact_force.h"
#include "mbs/surface_unilateral.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/mbs/rigid_test_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::VectorXd;

using testing::Advance;

/// The free-free test beam (its elastic modes; contact surface "tip", the face x = 0.6 m) as body
/// 0, a rigid ball as body 1, in a random state with the beam deformed and vibrating.
struct BeamAndBall {
  MultibodySystem system{Eigen::Vector3d::Zero()};
  MarkerRef origin, centre;
  sid::ContactSurface tip;
  Eigen::Index modes = 0;
  VectorXd y;
};

std::unique_ptr<BeamAndBall> MakeBeamAndBall(std::mt19937& rng) {
  auto scene = std::make_unique<BeamAndBall>();
  const testing::FeReducedBody& fe = testing::FreeFreeBeam();
  sid::ReducedBody data = testing::Reduce(fe, testing::KeepColumns(fe.basis, testing::ElasticColumns(fe.basis)));
  scene->tip = data.surfaces.at(0);
  scene->modes = static_cast<Eigen::Index>(data.mode_names.size());
  const int beam = scene->system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), false));
  const int ball = scene->system.AddBody(
      std::make_unique<RigidBody>("ball", 0.5, Eigen::Vector3d::Zero(), 1e-3 * Eigen::Matrix3d::Identity(),
                                  std::vector<RigidBodyMarker>{{"centre"}}));
  scene->origin = MarkerRef::OnBody(beam, scene->system.body(beam).FindMarker(FlexibleBody::kOriginMarker));
  scene->centre = MarkerRef::OnBody(ball, 0);
  const Eigen::Matrix3d R_WB = testing::RandomRotation(rng);
  VectorXd x_beam(7 + scene->modes), u_beam(6 + scene->modes);
  x_beam << testing::RigidPositions(testing::RandomVector(rng, 0.2), R_WB), 1e-4 * VectorXd::Random(scene->modes);
  u_beam << testing::RandomVector(rng, 0.5), testing::RandomVector(rng, 2.0), 0.3 * VectorXd::Random(scene->modes);
  scene->y = scene->system.NeutralState();
  scene->system.SetBodyState(beam, x_beam, u_beam, scene->y);
  // The ball 5 mm off the tip face, near its middle, moving.
  const Eigen::Vector3d p_tip = x_beam.head<3>() + R_WB * Eigen::Vector3d(0.6 + 0.005 + 0.02, 0.04, 0.03);
  VectorXd u_ball(6);
  u_ball << testing::RandomVector(rng, 0.5), testing::RandomVector(rng, 2.0);
  scene->system.SetBodyState(ball, testing::RigidPositions(p_tip, Eigen::Matrix3d::Identity()), u_ball, scene->y);
  return scene;
}

TEST(SurfaceContacts, JacobiansGiveEveryPointsGapRateOnADeformingBody) {
  std::mt19937 rng(5);
  std::unique_ptr<BeamAndBall> scene = MakeBeamAndBall(rng);
  MultibodySystem& system = scene->system;
  Eigen::Matrix3d R_WP = testing::RandomRotation(rng);
  system.AddUnilateralContact(std::make_unique<SurfacePlaneUnilateral>(
      "tip_on_plane", scene->origin, scene->tip, scene->modes,
      MarkerRef::Ground(Eigen::Vector3d(0.1, -0.2, 0.3), R_WP), UnilateralLaw{}));
  system.AddUnilateralContact(std::make_unique<SphereSurfaceUnilateral>("ball_on_tip", scene->centre, 0.02,
                                                                         scene->origin, scene->tip, scene->modes,
                                                                         UnilateralLaw{}));
  const VectorXd u = scene->y.tail(system.num_velocities());
  const double dt = 1e-6;
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    const UnilateralContact& contact = system.unilateral_contact(k);
    const std::vector<UnilateralContactKinematics> points = contact.Evaluate(0.0, system, scene->y);
    const std::vector<UnilateralContactKinematics> ahead = contact.Evaluate(0.0, system, Advance(system, scene->y, dt));
    const std::vector<UnilateralContactKinematics> behind =
        contact.Evaluate(0.0, system, Advance(system, scene->y, -dt));
    ASSERT_EQ(static_cast<int>(points.size()), contact.num_points());
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double rate = (ahead[p].g_N - behind[p].g_N) / (2.0 * dt);
      // Central differences of O(dt^2) and round-off on gaps of O(1) m at speeds of O(1) m/s
      // (measured: 5.7e-11 at most on these points).
      EXPECT_NEAR(points[p].W_N.dot(u), rate, 3e-10 * (1.0 + std::abs(rate))) << contact.name() << " point " << p;
      EXPECT_NEAR(points[p].n_W.cross(points[p].t1_W).dot(points[p].t2_W), 1.0, 1e-14);
    }
  }
  EXPECT_EQ(system.unilateral_contact(0).num_points(), static_cast<int>(scene->tip.vertices.rows()));
}

TEST(SurfaceContacts, SurfaceOnSurfaceJacobianGivesEveryVertexsGapRateBetweenTwoDeformingBodies) {
  // A second copy of the beam, turned half a turn about its z axis so that its tip face meets
  // the first beam's 5 mm away, both moving, turning and vibrating: node to surface, the first
  // face's vertices against the second's faces.
  std::mt19937 rng(7);
  std::unique_ptr<BeamAndBall> scene = MakeBeamAndBall(rng);
  MultibodySystem& system = scene->system;
  const VectorXd x_beam = system.BodyPositions(scene->y, 0), u_beam = system.BodyVelocities(scene->y, 0);
  const VectorXd x_ball = system.BodyPositions(scene->y, 1), u_ball = system.BodyVelocities(scene->y, 1);
  const testing::FeReducedBody& fe = testing::FreeFreeBeam();
  const int other = system.AddBody(std::make_unique<FlexibleBody>(
      "other", testing::Reduce(fe, testing::KeepColumns(fe.basis, testing::ElasticColumns(fe.basis))), false));
  const MarkerRef other_origin =
      MarkerRef::OnBody(other, system.body(other).FindMarker(FlexibleBody::kOriginMarker));
  VectorXd y = system.NeutralState();
  system.SetBodyState(0, x_beam, u_beam, y);
  system.SetBodyState(1, x_ball, u_ball, y);
  const Eigen::Vector3d p_WBo_W = y.head<3>();
  const Eigen::Matrix3d R_WB = Eigen::Quaterniond(y(3), y(4), y(5), y(6)).toRotationMatrix();
  const Eigen::Matrix3d R_WO = R_WB * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // The other beam's tip face (x = 0.6 in its frame) 5 mm beyond this one's, across from it and
  // shifted by a fraction of a cell, so that no vertex of this face lies level with an edge of
  // that one (where the nearest face, and with it the normal, switches: the gap has a kink) and
  // the vertices of one side overhang it (off the surface).
  const Eigen::Vector3d p_WOo_W = p_WBo_W + R_WB * Eigen::Vector3d(1.205, 0.1 - 0.013, 0.011);
  VectorXd x_other(7 + scene->modes), u_other(6 + scene->modes);
  x_other << testing::RigidPositions(p_WOo_W, R_WO), 1e-4 * VectorXd::Random(scene->modes);
  u_other << testing::RandomVector(rng, 0.5), testing::RandomVector(rng, 2.0), 0.3 * VectorXd::Random(scene->modes);
  system.SetBodyState(other, x_other, u_other, y);
  system.AddUnilateralContact(std::make_unique<SurfaceSurfaceUnilateral>(
      "tip_on_tip", scene->origin, scene->tip, scene->modes, other_origin, scene->tip, scene->modes, UnilateralLaw{}));
  const UnilateralContact& contact = system.unilateral_contact(0);
  const VectorXd u = y.tail(system.num_velocities());
  const double dt = 1e-6;
  const std::vector<UnilateralContactKinematics> points = contact.Evaluate(0.0, system, y);
  const std::vector<UnilateralContactKinematics> ahead = contact.Evaluate(0.0, system, Advance(system, y, dt));
  const std::vector<UnilateralContactKinematics> behind = contact.Evaluate(0.0, system, Advance(system, y, -dt));
  ASSERT_EQ(static_cast<int>(points.size()), static_cast<int>(scene->tip.vertices.rows()));
  double largest = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double rate = (ahead[p].g_N - behind[p].g_N) / (2.0 * dt);
    largest = std::max(largest, std::abs(points[p].W_N.dot(u) - rate));
    // Central differences of O(dt^2 g'''): an overhanging vertex's gap is its distance to the
    // edge, g''' ~ v^3 / g^2 ~ 7e3 m/s^3 here (measured: the largest difference 1.16e-5, 1.16e-7,
    // 1.21e-9 m/s at dt = 1e-4, 1e-5, 1e-6 s: second order, so W_N is the exact rate).
    EXPECT_NEAR(points[p].W_N.dot(u), rate, 1e-8) << "vertex " << p;
    EXPECT_GT(points[p].g_N, 0.0);
  }
  std::printf("surface on surface: largest |W_N u - dg/dt| %.3e m/s over %zu vertices\n", largest, points.size());
}

TEST(SurfaceContacts, CompliantSphereOnSurfaceDoesTheWorkOfItsForceAndHasItsVelocityJacobian) {
  std::mt19937 rng(9);
  std::unique_ptr<BeamAndBall> scene = MakeBeamAndBall(rng);
  MultibodySystem& system = scene->system;
  // A radius that reaches 1 mm into the face: the ball is in contact.
  const SphereSurfaceContact element("hit", scene->centre, 0.026, scene->origin, scene->tip, scene->modes,
                                     CompliantContactLaw{contact::LinearLaw(1e5, 50.0, 1.0), {}});
  const SphereSurfaceUnilateral kinematics("hit", scene->centre, 0.026, scene->origin, scene->tip, scene->modes,
                                           UnilateralLaw{});
  const VectorXd u = scene->y.tail(system.num_velocities());
  const UnilateralContactKinematics point = kinematics.Evaluate(0.0, system, scene->y).front();
  ASSERT_LT(point.g_N, 0.0);
  const double F_N = element.NormalForce(0.0, system, scene->y);
  EXPECT_NEAR(F_N, 1e5 * -point.g_N + 50.0 * -point.W_N.dot(u), 1e-9 * F_N);
  // Frictionless: the generalised force is W_N^T F_N, so it does the work F_N U_N.
  VectorXd h = VectorXd::Zero(system.num_velocities());
  element.AddForces(0.0, system, scene->y, h);
  EXPECT_NEAR(h.dot(u), F_N * point.W_N.dot(u), 1e-12 * std::abs(F_N));
  EXPECT_LT((h - F_N * point.W_N.transpose()).norm(), 1e-12 * std::abs(F_N));
  // dh/du against central differences of the forces in u.
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(u.size(), u.size()), dh_du = dh_dx;
  element.AddForceJacobian(0.0, system, scene->y, dh_dx, dh_du);
  const double du = 1e-6;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    VectorXd plus = scene->y, minus = scene->y;
    plus(system.num_positions() + j) += du;
    minus(system.num_positions() + j) -= du;
    VectorXd h_plus = VectorXd::Zero(u.size()), h_minus = VectorXd::Zero(u.size());
    element.AddForces(0.0, system, plus, h_plus);
    element.AddForces(0.0, system, minus, h_minus);
    // The forces are linear in u here (linear damping): the quotients are exact up to the
    // round-off of forces of ~100 N over 2e-6 (measured: 1.0e-8 at most).
    EXPECT_LT(((h_plus - h_minus) / (2.0 * du) - dh_du.col(j)).norm(), 1e-7) << j;
  }
}

TEST(SurfaceContacts, CompliantSurfaceOnPlaneLoadsEachPenetratingVertexThroughItsJacobian) {
  std::mt19937 rng(21);
  std::unique_ptr<BeamAndBall> scene = MakeBeamAndBall(rng);
  MultibodySystem& system = scene->system;
  // The plane through the tip face's first vertex, normal against the face's: about half the
  // (slightly deformed, tilted) face's vertices penetrate.
  const SurfacePlaneUnilateral probe("probe", scene->origin, scene->tip, scene->modes,
                                     MarkerRef::Ground(Eigen::Vector3d::Zero()), UnilateralLaw{});
  const std::vector<UnilateralContactKinematics> at_origin = probe.Evaluate(0.0, system, scene->y);
  const Eigen::Vector3d p0 = at_origin[0].p_WA_W;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const UnilateralContactKinematics& k : at_origin) mean += k.p_WA_W / static_cast<double>(at_origin.size());
  const Eigen::Vector3d n = (p0 - mean).normalized();
  const Eigen::Matrix3d R_WP = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -n).toRotationMatrix();
  const MarkerRef plane = MarkerRef::Ground(mean, R_WP);
  const double k = 1e6, c = 20.0;
  const SurfacePlaneContact element("tip", scene->origin, scene->tip, scene->modes, plane,
                                    CompliantContactLaw{contact::LinearLaw(k, c, 1.0), {}});
  const SurfacePlaneUnilateral kinematics("tip", scene->origin, scene->tip, scene->modes, plane, UnilateralLaw{});
  const VectorXd u = scene->y.tail(system.num_velocities());
  VectorXd expected = VectorXd::Zero(u.size());
  double total = 0.0;
  int penetrating = 0;
  for (const UnilateralContactKinematics& point : kinematics.Evaluate(0.0, system, scene->y)) {
    if (!(point.g_N < 0.0)) continue;
    const double F = std::max(0.0, k * -point.g_N + c * -point.W_N.dot(u));
    expected += F * point.W_N.transpose();
    total += F;
    ++penetrating;
  }
  ASSERT_GT(penetrating, 0);
  ASSERT_LT(penetrating, static_cast<int>(scene->tip.vertices.rows()));
  VectorXd h = VectorXd::Zero(u.size());
  element.AddForces(0.0, system, scene->y, h);
  EXPECT_LT((h - expected).norm(), 1e-12 * expected.norm());
  EXPECT_NEAR(element.NormalForce(system, scene->y), total, 1e-12 * total);
}

}  // namespace
}  // namespace flexmbs::mbs
