// A circle against a finite segment whose ends act as corners (contact::SphereSegment,
// mbs::SphereSegmentUnilateral, scene type sphere_segment; docs/contact.md "Planar scenes"): the
// geometry against hand-computed closed forms in each region (the segment, beyond an end above it:
// the corner, beyond and below: the side), continuous where the regions meet; W_N against the
// gap's difference quotients along a motion; a frictionless disk sliding off a segment's end
// leaves the corner at the closed-form angle cos(theta) = (2 + v0^2 / (g r)) / 3, at the time the
// quadrature of the pivoting motion gives, and flies on the closed-form parabola (event-driven;
// Moreau-Jean within a step and to first order in h); bad ends refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "contact/geometry/sphere_segment.h"
#include "mbs/event_driven.h"
#include "mbs/planar.h"
#include "mbs/rigid_body.h"
#include "mbs/sphere_segment_unilateral.h"
#include "tests/input_error.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kG = 9.81, kMass = 2.0, kRadius = 0.1;

/// Expects the contact's gap, normal and points (tolerance `tol` [m]) and a right-handed frame.
void ExpectContact(const contact::PointContactKinematics& c, double g_N, const Vector3d& n_W,
                   const Vector3d& p_WA_W, const Vector3d& p_WB_W, double tol = 1e-15) {
  EXPECT_NEAR(c.g_N, g_N, tol);
  EXPECT_LT((c.n_W - n_W).norm(), tol) << c.n_W.transpose();
  EXPECT_LT((c.p_WA_W - p_WA_W).norm(), tol) << c.p_WA_W.transpose();
  EXPECT_LT((c.p_WB_W - p_WB_W).norm(), tol) << c.p_WB_W.transpose();
  EXPECT_LT((c.n_W.cross(c.t1_W) - c.t2_W).norm(), 1e-15);
  EXPECT_LT((c.p_WA_W - c.p_WB_W - c.g_N * c.n_W).norm(), tol);
}

TEST(SphereSegment, EachRegionGivesItsClosedFormContact) {
  // The segment from (0, 0, 0) to (2, 0, 0) extruded along z: outward normal z x x = +y.
  const contact::Segment segment{Vector3d::Zero(), Vector3d(2.0, 0.0, 0.0), Vector3d::UnitZ()};
  const auto at = [&](const Vector3d& c) { return contact::SphereSegment({c, 0.1}, segment); };
  // Over the segment: the line.
  ExpectContact(at({1.0, 0.5, 0.0}), 0.4, {0, 1, 0}, {1.0, 0.4, 0.0}, {1.0, 0.0, 0.0});
  // Beyond E2, above: the corner, 3-4-5 from it.
  ExpectContact(at({2.3, 0.4, 0.0}), 0.4, {0.6, 0.8, 0}, {2.24, 0.32, 0.0}, {2.0, 0.0, 0.0});
  // Beyond E1, above, off the plane z = 0: the edge's point at the centre's z.
  ExpectContact(at({-0.3, 0.4, 0.7}), 0.4, {-0.6, 0.8, 0}, {-0.24, 0.32, 0.7}, {0.0, 0.0, 0.7});
  // Beyond E2, below the top: E2's side (normal +x), and E1's side penetrated by 0.05 m.
  ExpectContact(at({2.3, -0.2, 0.0}), 0.2, {1, 0, 0}, {2.2, -0.2, 0.0}, {2.0, -0.2, 0.0});
  ExpectContact(at({-0.05, -0.5, 0.0}), -0.05, {-1, 0, 0}, {0.05, -0.5, 0.0}, {0.0, -0.5, 0.0});
  // The ends swapped: the free side is -y.
  const contact::Segment reversed{segment.p_WE2_W, segment.p_WE1_W, Vector3d::UnitZ()};
  ExpectContact(contact::SphereSegment({{1.0, -0.5, 0.0}, 0.1}, reversed), 0.4, {0, -1, 0},
                {1.0, -0.4, 0.0}, {1.0, 0.0, 0.0});
}

TEST(SphereSegment, RegionsMeetContinuously) {
  const contact::Segment segment{Vector3d::Zero(), Vector3d(2.0, 0.0, 0.0), Vector3d::UnitZ()};
  constexpr double kStep = 1e-9;
  double worst = 0.0;
  // Segment | corner at s = L (above), corner | side at the top's level (beyond E2), both ends.
  const std::vector<std::pair<Vector3d, Vector3d>> crossings = {
      {{2.0 - kStep, 0.3, 0.0}, {2.0 + kStep, 0.3, 0.0}},
      {{2.4, kStep, 0.0}, {2.4, -kStep, 0.0}},
      {{kStep, 0.3, 0.0}, {-kStep, 0.3, 0.0}},
      {{-0.4, kStep, 0.0}, {-0.4, -kStep, 0.0}}};
  for (const auto& [before, after] : crossings) {
    const contact::PointContactKinematics a = contact::SphereSegment({before, 0.1}, segment);
    const contact::PointContactKinematics b = contact::SphereSegment({after, 0.1}, segment);
    worst = std::max(
        {worst, std::abs(a.g_N - b.g_N), (a.n_W - b.n_W).norm(), (a.p_WB_W - b.p_WB_W).norm()});
  }
  std::printf(
      "across the regions' borders (2e-9 m apart): largest change of gap, normal, foot %.2e\n",
      worst);
  // Measured: 3.3e-9 (the corner's normal turns by 2e-9 / 0.3 across s = L; the rest O(2e-9)).
  EXPECT_LT(worst, 3e-8);
}

TEST(SphereSegment, ACentreOnTheCornerHasNoNormal) {
  const contact::Segment segment{Vector3d::Zero(), Vector3d(2.0, 0.0, 0.0), Vector3d::UnitZ()};
  EXPECT_THROW(contact::SphereSegment({{2.0 + 4e-16, 1e-16, 0.0}, 0.1}, segment),
               contact::DegenerateContactError);
}

/// Disk (kMass, kRadius, J_z = m r^2 / 2) centred at p0 moving with v0 (gravity -y), and a plate
/// (rigid, at q0 turned by `turn` about z, moving with v_plate, w_plate) carrying the segment
/// from (-1, 0, 0) to (0, 0, 0) of its marker (normal +y of the marker); contact "edge", mu.
/// With `plate_on_ground` the segment is on the ground at q0 instead.
testing::ContactScene DiskAndSegment(const Vector3d& p0, const Vector3d& v0, double friction,
                                     bool plate_on_ground, const Vector3d& q0 = Vector3d::Zero(),
                                     double turn = 0.0, const Vector3d& v_plate = Vector3d::Zero(),
                                     double w_plate = 0.0) {
  testing::ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, -kG, 0.0)),
                              VectorXd()};
  MultibodySystem& system = *scene.system;
  const Matrix3d inertia = Vector3d(0.25, 0.25, 0.5).asDiagonal() * (kMass * kRadius * kRadius);
  const int disk = system.AddBody(std::make_unique<RigidBody>(
      "disk", kMass, Vector3d::Zero(), inertia,
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  int plate = -1;
  if (!plate_on_ground) {
    plate = system.AddBody(std::make_unique<RigidBody>(
        "plate", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 0.1,
        std::vector<RigidBodyMarker>{{"edge", Vector3d::Zero(), Matrix3d::Identity()}}));
  }
  const MarkerRef segment =
      plate_on_ground
          ? MarkerRef::Ground(q0, Eigen::AngleAxisd(turn, Vector3d::UnitZ()).toRotationMatrix())
          : system.Marker("plate", "edge");
  system.AddUnilateralContact(std::make_unique<SphereSegmentUnilateral>(
      "edge", system.Marker("disk", "centre"), segment, Vector3d(-1.0, 0.0, 0.0), Vector3d::Zero(),
      kRadius, UnilateralLaw{0.0, friction}));
  scene.y0 = system.NeutralState();
  VectorXd x(7), u = VectorXd::Zero(6);
  x << p0, 1.0, 0.0, 0.0, 0.0;
  u.head<3>() = v0;
  system.SetBodyState(disk, x, u, scene.y0);
  if (plate >= 0) {
    x << q0, std::cos(turn / 2.0), 0.0, 0.0, std::sin(turn / 2.0);
    u << v_plate, 0.0, 0.0, w_plate;
    system.SetBodyState(plate, x, u, scene.y0);
  }
  return scene;
}

TEST(SphereSegmentUnilateral, NormalRowIsTheGapsRateInEachRegion) {
  // The plate turned by 0.3 rad, moving and turning; the disk's centre over the segment, over the
  // corner at (0, 0) of the plate's marker and beside its side (below the top), each moving.
  const Matrix3d R = Eigen::AngleAxisd(0.3, Vector3d::UnitZ()).toRotationMatrix();
  const Vector3d q0(0.2, -0.1, 0.0);
  double worst = 0.0;
  for (const Vector3d& p_M :
       {Vector3d(-0.5, 0.12, 0.0), Vector3d(0.06, 0.09, 0.0), Vector3d(0.13, -0.2, 0.0)}) {
    testing::ContactScene scene = DiskAndSegment(q0 + R * p_M, Vector3d(0.7, -0.4, 0.0), 0.0, false,
                                                 q0, 0.3, Vector3d(-0.3, 0.5, 0.0), 1.7);
    MultibodySystem& system = *scene.system;
    // The disk turns too (its contact point's velocity has no normal part: n passes the centre).
    scene.y0(system.num_positions() + 5) = 2.5;
    const auto u = scene.y0.tail(system.num_velocities());
    const UnilateralContact& contact = system.unilateral_contact(0);
    const UnilateralContactKinematics k = contact.Evaluate(0.0, system, scene.y0)[0];
    constexpr double kEps = 1e-6;
    VectorXd plus = scene.y0, minus = scene.y0;
    system.DisplacePositions(kEps * u, plus);
    system.DisplacePositions(-kEps * u, minus);
    const double rate =
        (contact.Evaluate(0.0, system, plus)[0].g_N - contact.Evaluate(0.0, system, minus)[0].g_N) /
        (2.0 * kEps);
    worst = std::max(worst, std::abs(k.W_N.dot(u) - rate));
  }
  std::printf("W_N u against the gap's central difference (1e-6 s), three regions: %.2e m/s\n",
              worst);
  // Measured: 4.6e-11 m/s (the difference quotient's truncation and round-off).
  EXPECT_LT(worst, 4e-10);
}

/// A frictionless disk sliding along the segment y = 0, x in [-1, 0], from x = -0.2 m at v0 reaches
/// its end at t_c = 0.2 / v0; it then pivots about the corner (its centre on the circle of radius r
/// about it; no friction, so it does not turn), v^2 = v0^2 + 2 g r (1 - cos theta), and the normal
/// force m g cos(theta) - m v^2 / r vanishes at cos(theta*) = (2 + v0^2 / (g r)) / 3 (derived from
/// the energy and the radial equation of the pivoting motion; v0 = 0 gives the textbook particle
/// leaving a smooth sphere at cos(theta) = 2/3), at t* = t_c + int_0^theta* r / v(theta) dtheta;
/// then it flies on a parabola from (r sin theta*, r cos theta*) at sqrt(g r cos theta*) along the
/// circle.
struct SlideOff {
  static constexpr double v0 = 0.5;
  double cos_star = 0.0, theta_star = 0.0, t_star = 0.0;

  SlideOff() {
    cos_star = (2.0 + v0 * v0 / (kG * kRadius)) / 3.0;
    theta_star = std::acos(cos_star);
    constexpr int kIntervals = 4000;  // composite Simpson on a smooth integrand
    double integral = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
      const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      const double theta = theta_star * i / kIntervals;
      integral +=
          weight * kRadius / std::sqrt(v0 * v0 + 2.0 * kG * kRadius * (1.0 - std::cos(theta)));
    }
    t_star = 0.2 / v0 + integral * theta_star / kIntervals / 3.0;
  }
  /// The centre's position at t >= t_star [m].
  Vector3d CentreInFlight(double t) const {
    const double flight = t - t_star, v_star = std::sqrt(kG * kRadius * cos_star);
    const Vector3d p_star(kRadius * std::sin(theta_star), kRadius * cos_star, 0.0);
    const Vector3d v_dir(cos_star, -std::sin(theta_star), 0.0);
    return p_star + v_star * v_dir * flight + 0.5 * Vector3d(0.0, -kG, 0.0) * flight * flight;
  }
  /// The scene: the disk at x = -0.2 m on the ground's segment, planar.
  static testing::ContactScene Scene() {
    testing::ContactScene scene =
        DiskAndSegment(Vector3d(-0.2, kRadius, 0.0), Vector3d(v0, 0.0, 0.0), 0.0, true);
    MakePlanar(*scene.system, scene.y0);
    return scene;
  }
};

TEST(SphereSegmentUnilateral, ADiskSlidesOffTheEndAtTheClosedFormAngleAndTime) {
  const SlideOff exact;
  // SciPy's quad of the same integral (estimated error 1.3e-15): 0.11681551345886043 s.
  EXPECT_NEAR(exact.t_star - 0.4, 0.11681551345886043, 1e-14);
  testing::ContactScene scene = SlideOff::Scene();
  constexpr double kEnd = 0.6;  // t* = 0.5168 s, then 0.083 s of flight
  const testing::EventRun run = testing::RunEventDriven(scene, kEnd, 0.01, 1e-4);
  std::vector<double> separations;
  for (const ContactEvent& event : run.events) {
    if (event.kind == ContactEventKind::kSeparation) separations.push_back(event.time);
  }
  ASSERT_EQ(separations.size(), 1u) << run.events.size() << " events";
  const MultibodySystem& system = *scene.system;
  const double end_error =
      (system.BodyPositions(run.y.back(), 0).head<3>() - exact.CentreInFlight(kEnd)).norm();
  const double spin = system.BodyVelocities(run.y.back(), 0)(5);
  std::printf(
      "disk off the segment's end: separation at %.15f s, closed form %.15f s (error %.2e s); "
      "position at %.2f s off the closed-form flight by %.2e m; spin %.1e rad/s; %zu events\n",
      separations[0], exact.t_star, separations[0] - exact.t_star, kEnd, end_error, spin,
      run.events.size());
  // Measured: separation 6.6e-11 s late (the root of the contact force, which leaves 0 linearly),
  // end position 5.7e-12 m (the motion is continuous through the separation), spin 6.0e-17 rad/s
  // (round-off: no friction turns it).
  EXPECT_NEAR(separations[0], exact.t_star, 6e-10);
  EXPECT_LT(end_error, 5e-11);
  EXPECT_LT(std::abs(spin), 1e-15);
}

TEST(SphereSegmentUnilateral, MoreauJeanLetsTheDiskGoWithinAStepOfTheClosedFormTime) {
  const SlideOff exact;
  constexpr double kStep = 1e-4, kEnd = 0.6;
  testing::ContactScene scene = SlideOff::Scene();
  const testing::StepHistory history = testing::RunMoreauJean(scene, kStep, kEnd);
  // The last step with an impulse: the normal force goes to 0 linearly at t*, so the step
  // containing t* may carry none.
  std::size_t last = 0;
  for (std::size_t k = 1; k < history.steps.size(); ++k) {
    if (history.steps[k].contacts[0].P_N > 0.0) last = k;
  }
  const double end_error =
      (scene.system->BodyPositions(history.y.back(), 0).head<3>() - exact.CentreInFlight(kEnd))
          .norm();
  std::printf(
      "Moreau-Jean (h = %g s): the last step with an impulse ends at %.6f s, closed form t* %.6f s "
      "(%.2e s); position at %.2f s off the closed-form flight by %.2e m\n",
      kStep, history.t[last], exact.t_star, history.t[last] - exact.t_star, kEnd, end_error);
  // Measured: the last impulse's step ends 1.55e-5 s (0.16 h) before t*, the position 7.7e-5 m
  // off (the scheme's first order in h).
  EXPECT_LT(std::abs(history.t[last] - exact.t_star), kStep);
  EXPECT_LT(end_error, 2e-4);
}

TEST(SphereSegmentUnilateral, BadEndsAreRefused) {
  const MarkerRef disk = MarkerRef::OnBody(0, 0);
  const auto build = [&](const Vector3d& e1, const Vector3d& e2) {
    SphereSegmentUnilateral("edge", MarkerRef::Ground(Vector3d::Zero(), Matrix3d::Identity()), disk,
                            e1, e2, 0.1, UnilateralLaw{0.0, 0.0});
  };
  EXPECT_EQ(
      flexmbs::testing::InputErrorMessage([&] { build(Vector3d(1, 0, 0), Vector3d(1, 0, 0)); }),
      "contact 'edge': the segment's ends (1, 0, 0) and (1, 0, 0) m must be finite and apart");
  EXPECT_EQ(
      flexmbs::testing::InputErrorMessage([&] { build(Vector3d(0, 0, 0), Vector3d(1, 0, 0.5)); }),
      "contact 'edge': the segment's ends (0, 0, 0) and (1, 0, 0.5) m must lie at one z of their "
      "marker (the "
      "segment is extruded along its z axis)");
}

}  // namespace
}  // namespace flexmbs::mbs
