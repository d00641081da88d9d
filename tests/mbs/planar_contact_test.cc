// Contact in planar scenes (mbs/planar.h, docs/contact.md "Planar scenes"): the circle-on-line
// contact is the sphere_plane contact with the plane containing W z, solved with the one in-plane
// tangent (d = 2, Coulomb's two-sided cone). A disk on an incline rolls at 2/3 g sin a below the
// friction limit and slides at g (sin a - mu cos a) above it (Moreau-Jean and event-driven,
// against the closed forms; Moreau-Jean also against the spatial run of the same scene); a circle bouncing on a line with e = 0.9 hits at
// the closed-form times (event-driven and Moreau-Jean).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "mbs/event_driven.h"
#include "mbs/planar.h"
#include "mbs/rigid_body.h"
#include "mbs/unilateral_contact.h"
#include "tests/input_error.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::ContactScene;

constexpr double kG = 9.81, kMass = 2.0, kRadius = 0.1;

/// A disk (kMass, kRadius; J_z = m r^2 / 2) touching (1e-12 m into) the line through W's origin
/// along (cos a, sin a, 0) from above, at rest; gravity -y. The line is a ground plane marker
/// whose z axis is the line's normal n = (-sin a, cos a, 0); contact "line" with e, mu. The disk's
/// centre starts `height` [m] above its touching position along n.
ContactScene DiskOnLine(double angle, double restitution, double friction, double height = -1e-12) {
  ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, -kG, 0.0)), VectorXd()};
  MultibodySystem& system = *scene.system;
  const Matrix3d inertia = Vector3d(0.25, 0.25, 0.5).asDiagonal() * (kMass * kRadius * kRadius);
  const int disk = system.AddBody(std::make_unique<RigidBody>(
      "disk", kMass, Vector3d::Zero(), inertia,
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  const Matrix3d R_WP = Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix() *
                        Eigen::AngleAxisd(-std::numbers::pi / 2.0, Vector3d::UnitX()).toRotationMatrix();
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "line", system.Marker("disk", "centre"), MarkerRef::Ground(Vector3d::Zero(), R_WP), kRadius,
      UnilateralLaw{restitution, friction}));
  scene.y0 = system.NeutralState();
  VectorXd x(7);
  x << (kRadius + height) * R_WP.col(2), 1.0, 0.0, 0.0, 0.0;
  system.SetBodyState(disk, x, VectorXd::Zero(6), scene.y0);
  return scene;
}

/// The disk's velocity down the line and its rolling speed w_z r (both [m/s]) in state y.
struct DiskMotion {
  double speed = 0.0, rolling = 0.0;
};
DiskMotion Motion(const MultibodySystem& system, const VectorXd& y, double angle) {
  const auto u = y.tail(system.num_velocities());
  const Vector3d down(-std::cos(angle), -std::sin(angle), 0.0);
  // Rolling down the line (to -x for a small angle) turns the disk positively about z.
  return {down.dot(u.head<3>()), u(5) * kRadius};
}

TEST(PlanarContact, DiskOnAnInclineRollsOrSlidesWithTheClosedFormAcceleration) {
  constexpr double kAngle = 0.3, kStep = 1e-3, kEnd = 0.5;
  // Rolling needs mu >= tan(a) / 3 = 0.1031: 0.3 rolls, 0.05 slides.
  for (const double mu : {0.3, 0.05}) {
    const bool rolls = mu >= std::tan(kAngle) / 3.0;
    const double expected = rolls ? 2.0 / 3.0 * kG * std::sin(kAngle) : kG * (std::sin(kAngle) - mu * std::cos(kAngle));
    ContactScene planar = DiskOnLine(kAngle, 0.0, mu), spatial = DiskOnLine(kAngle, 0.0, mu);
    MakePlanar(*planar.system, planar.y0);
    const testing::StepHistory a = testing::RunMoreauJean(planar, kStep, kEnd);
    const testing::StepHistory b = testing::RunMoreauJean(spatial, kStep, kEnd);
    const DiskMotion end = Motion(*planar.system, a.y.back(), kAngle);
    const double acceleration = end.speed / a.t.back();
    const double spatial_difference = (a.y.back() - b.y.back()).cwiseAbs().maxCoeff();
    const double slip = end.speed - end.rolling;
    std::printf("mu %.2f (%s): acceleration %.12f m/s^2, closed form %.12f, relative error %.2e; slip %.3e m/s "
                "(closed form %.3e); planar vs spatial %.2e; sliding reported %d\n",
                mu, rolls ? "rolls" : "slides", acceleration, expected, acceleration / expected - 1.0, slip,
                rolls ? 0.0 : (expected - 2.0 * kG * mu * std::cos(kAngle)) * a.t.back(), spatial_difference,
                a.steps.back().contacts[0].sliding ? 1 : 0);
    // Measured: acceleration 2.2e-16 (rolls) and 2.8e-15 (slides) relative, slip 1.1e-16 m/s
    // rolling, planar against spatial 3.6e-15 (the spatial run's cone has two tangents, the
    // out-of-plane one idle).
    EXPECT_NEAR(acceleration / expected, 1.0, 3e-14);
    EXPECT_EQ(a.steps.back().contacts[0].sliding, !rolls);
    if (rolls) {
      EXPECT_LT(std::abs(slip), 1e-14);
    } else {
      // Sliding: w_z' = mu m g cos(a) r / J, so slip = (a - 2 mu g cos a) t.
      EXPECT_NEAR(slip, (expected - 2.0 * kG * mu * std::cos(kAngle)) * a.t.back(), 1e-13);
    }
    EXPECT_LT(spatial_difference, 4e-14);
  }
}

TEST(PlanarContact, CircleBouncingOnALineHitsAtTheClosedFormTimes) {
  constexpr double e = 0.9, kGap0 = 1.0, kRestVelocity = 1e-4;
  const double v1 = std::sqrt(2.0 * kG * kGap0), t1 = std::sqrt(2.0 * kGap0 / kG);
  // Impact k (from 1) at t_k with speed v_k = e^(k-1) v_1: t_k+1 = t_k + 2 e v_k / g.
  std::vector<double> exact = {t1};
  for (double speed = v1; exact.size() < 12; speed *= e) exact.push_back(exact.back() + 2.0 * e * speed / kG);

  // Event-driven.
  ContactScene scene = DiskOnLine(0.0, e, 0.0, kGap0);
  MakePlanar(*scene.system, scene.y0);
  const testing::EventRun run = testing::RunEventDriven(scene, exact.back() + 0.01, 0.01, kRestVelocity);
  std::vector<double> impacts;
  for (const ContactEvent& event : run.events) {
    if (event.kind == ContactEventKind::kImpact) impacts.push_back(event.time);
  }
  ASSERT_GE(impacts.size(), exact.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k) worst = std::max(worst, std::abs(impacts[k] - exact[k]));
  // Moreau-Jean (h = 1e-3): the step whose end holds the impulse of impact k contains t_k.
  ContactScene stepped = DiskOnLine(0.0, e, 0.0, kGap0);
  MakePlanar(*stepped.system, stepped.y0);
  constexpr double kStep = 1e-3;
  const testing::StepHistory history = testing::RunMoreauJean(stepped, kStep, exact.back() + 0.01);
  std::vector<double> impact_steps;
  for (std::size_t k = 1; k < history.steps.size(); ++k) {
    const ContactStepResult& c = history.steps[k].contacts[0];
    const bool started = c.P_N > 0.0 && !(history.steps[k - 1].contacts[0].P_N > 0.0);
    if (started) impact_steps.push_back(history.t[k]);
  }
  ASSERT_GE(impact_steps.size(), exact.size());
  // Its impact times drift by the velocity-level law's step error: each flight (from the first
  // impact's step end, or from t = 0) is compared with the closed form's.
  double worst_step = 0.0, worst_total = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    const double flight = impact_steps[k] - (k == 0 ? 0.0 : impact_steps[k - 1]);
    const double exact_flight = exact[k] - (k == 0 ? 0.0 : exact[k - 1]);
    worst_step = std::max(worst_step, std::abs(flight - exact_flight));
    worst_total = std::max(worst_total, std::abs(impact_steps[k] - exact[k]));
  }
  std::printf("circle on a line, e = 0.9: %zu impacts compared; event-driven largest impact-time error %.2e s; "
              "Moreau-Jean (h = %g s): each flight within %.2e s of the closed form's, impact %zu %.2e s late\n",
              exact.size(), worst, kStep, worst_step, exact.size(), worst_total);
  // Measured: event-driven 4.1e-13 s; Moreau-Jean's flights 1.5e-3 s (the first impact found a
  // step late), 7.5e-3 s late after 12 flights.
  EXPECT_LT(worst, 4e-12);
  EXPECT_LT(worst_step, 2.0 * kStep);
}

TEST(PlanarContact, DiskOnAnInclineEventDrivenRollsOrSlidesWithTheClosedFormAcceleration) {
  constexpr double kAngle = 0.3, kEnd = 0.5;
  for (const double mu : {0.3, 0.05}) {
    const bool rolls = mu >= std::tan(kAngle) / 3.0;
    const double expected = rolls ? 2.0 / 3.0 * kG * std::sin(kAngle) : kG * (std::sin(kAngle) - mu * std::cos(kAngle));
    ContactScene scene = DiskOnLine(kAngle, 0.0, mu);
    MakePlanar(*scene.system, scene.y0);
    const testing::EventRun run = testing::RunEventDriven(scene, kEnd, 0.05, 1e-4);
    const DiskMotion end = Motion(*scene.system, run.y.back(), kAngle);
    const double acceleration = end.speed / run.t.back(), slip = end.speed - end.rolling;
    const double expected_slip = rolls ? 0.0 : (expected - 2.0 * kG * mu * std::cos(kAngle)) * run.t.back();
    std::printf("event-driven, mu %.2f (%s): acceleration relative error %.2e, slip %.3e m/s (error %.2e), "
                "%ld events, sliding reported %d\n",
                mu, rolls ? "rolls" : "slides", acceleration / expected - 1.0, slip, slip - expected_slip,
                run.statistics.event_driven.events, run.contacts.back().contacts[0].sliding ? 1 : 0);
    // Measured: acceleration 5.6e-16 (rolls, no event) and 3.0e-14 (slides: one event, the slip
    // beginning) relative, slip 2.2e-16 and 1.1e-13 m/s.
    EXPECT_NEAR(acceleration / expected, 1.0, 3e-13);
    EXPECT_NEAR(slip, expected_slip, 1e-12);
    EXPECT_EQ(run.contacts.back().contacts[0].sliding, !rolls);
  }
}

TEST(PlanarContact, AContactNormalOutOfThePlaneIsRefused) {
  // The ground plane's normal turned 0.2 rad out of the plane about the line's direction.
  ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, -kG, 0.0)), VectorXd()};
  MultibodySystem& system = *scene.system;
  system.AddBody(std::make_unique<RigidBody>("disk", kMass, Vector3d::Zero(), Matrix3d::Identity() * 1e-3,
                                             std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  const Matrix3d R_WP = Eigen::AngleAxisd(-std::numbers::pi / 2.0 + 0.2, Vector3d::UnitX()).toRotationMatrix();
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "tilted", system.Marker("disk", "centre"), MarkerRef::Ground(Vector3d(0.0, -1.0, 0.0), R_WP), kRadius,
      UnilateralLaw{0.0, 0.0}));
  scene.y0 = system.NeutralState();
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { MakePlanar(system, scene.y0); }),
            "contact 'tilted': normal (0, 0.980067, 0.198669) is out of the plane xy");
}

}  // namespace
}  // namespace flexmbs::mbs
