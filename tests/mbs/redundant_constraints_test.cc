// Redundant constraints (docs/mbs.md, "Redundant constraints"): a planar four-bar of revolute
// joints in 3-D repeats 3 out-of-plane equations per loop. The run drops them at t0 and must
// move exactly like the same four-bar closed without redundancy (spherical joints at both ends
// of the coupler), with the same in-plane joint loads; a dropped row that stops holding is
// reported as a change of the redundancy; and `flexmbs simulate` runs such a scene and says
// what it dropped (report, --json, results provenance).
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "core/h5_file.h"
#include "mbs/constraint_projection.h"
#include "mbs/constraint_redundancy.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/simulation_error.h"
#include "rigid_test_support.h"
#include "tests/app/flexmbs_process.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::RigidPositions;

constexpr double kGravity = 9.81;
// Both models are integrated to these tolerances and projected to 1e-11 m after every step: their
// difference is the integrators' global error, below the required 1e-8.
constexpr double kRelativeTolerance = 1e-12, kAbsoluteTolerance = 1e-14;
constexpr double kSameMotion = 1e-8;    // [m] body origins and [1] Euler parameters, the task's requirement
constexpr double kSameLoads = 1e-6;     // [N] on loads of ~10 N: the multipliers are u' level

// A four-bar in the W x-y plane (gravity along -y): ground pivots O = (0, 0) and D = (d, 0),
// crank O-A, coupler A-B, rocker D-B, released from rest at crank angle theta0.
struct FourBarGeometry {
  double crank = 1.0, coupler = 2.2, rocker = 1.5, ground = 2.0;  // [m]
  double theta0 = std::numbers::pi / 3;                            // [rad]
};

Eigen::Matrix3d Rz(double angle) { return Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix(); }

// The upper intersection of the circles |x - a| = ra and |x - b| = rb.
Vector2d CircleIntersection(const Vector2d& a, double ra, const Vector2d& b, double rb) {
  const double d = (b - a).norm();
  const double along = (ra * ra - rb * rb + d * d) / (2.0 * d);
  const Vector2d e = (b - a) / d;
  return a + along * e + std::sqrt(ra * ra - along * along) * Vector2d(-e.y(), e.x());
}

// A slender link of `length` along B x with markers "a" (x = 0) and "b" (x = length), both with
// the axes of B; a uniform bar of 1 kg/m (inertia of a bar about x, y, z with a small section).
int AddLink(MultibodySystem& system, const std::string& name, double length) {
  const double mass = length;
  const double bending = mass * length * length / 12.0;
  return system.AddBody(std::make_unique<RigidBody>(
      name, mass, 0.5 * length * Vector3d::UnitX(), Vector3d(1e-4 * mass, bending, bending).asDiagonal(),
      std::vector<RigidBodyMarker>{{"a", Vector3d::Zero(), Eigen::Matrix3d::Identity()},
                                   {"b", length * Vector3d::UnitX(), Eigen::Matrix3d::Identity()},
                                   {"c", 0.5 * length * Vector3d::UnitX(), Eigen::Matrix3d::Identity()}}));
}

// Puts link b (markers a, b) from p to q in the plane, at rest.
void PlaceLink(const MultibodySystem& system, int b, const Vector2d& p, const Vector2d& q, Eigen::VectorXd& y) {
  const Vector2d d = q - p;
  system.SetBodyState(b, RigidPositions(Vector3d(p.x(), p.y(), 0.0), Rz(std::atan2(d.y(), d.x()))),
                      Eigen::VectorXd::Zero(6), y);
}

// The four-bar; `coupler_joint` closes the coupler at both ends (revolute: redundant, spherical:
// not; the coupler's idle spin about A-B stays 0 as nothing drives it).
struct FourBar {
  MultibodySystem system{Vector3d(0.0, -kGravity, 0.0)};
  Eigen::VectorXd y0;
  Vector2d A, B;

  FourBar(const FourBarGeometry& g, JointType coupler_joint) {
    AddLink(system, "crank", g.crank);
    AddLink(system, "coupler", g.coupler);
    AddLink(system, "rocker", g.rocker);
    const Vector2d D(g.ground, 0.0);
    system.AddJoint(Joint("ground_crank", JointType::kRevolute, MarkerRef::Ground(Vector3d::Zero()), system.Marker("crank", "a")));
    system.AddJoint(Joint("crank_coupler", coupler_joint, system.Marker("crank", "b"), system.Marker("coupler", "a")));
    system.AddJoint(Joint("coupler_rocker", coupler_joint, system.Marker("coupler", "b"), system.Marker("rocker", "b")));
    system.AddJoint(Joint("rocker_ground", JointType::kRevolute, MarkerRef::Ground(Vector3d(D.x(), D.y(), 0.0)),
                          system.Marker("rocker", "a")));
    A = g.crank * Vector2d(std::cos(g.theta0), std::sin(g.theta0));
    B = CircleIntersection(A, g.coupler, D, g.rocker);
    y0 = system.NeutralState();
    PlaceLink(system, 0, Vector2d::Zero(), A, y0);
    PlaceLink(system, 1, A, B, y0);
    PlaceLink(system, 2, D, B, y0);
  }
};

struct History {
  std::vector<Eigen::VectorXd> states, loads;  // per output: y; in-plane joint forces (x, y per joint)
  SimulationStatistics statistics;
};

History Integrate(MultibodySystem& system, const Eigen::VectorXd& y0, double end_time, double output_interval) {
  SimulationOptions options;
  options.end_time = end_time;
  options.output_interval = output_interval;
  options.integrator.relative_tolerance = kRelativeTolerance;
  options.integrator.absolute_tolerance = kAbsoluteTolerance;
  History run;
  run.statistics = Simulate(system, options, y0, [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& lambda) {
    run.states.push_back(y);
    Eigen::VectorXd loads(2 * system.num_joints());
    for (int k = 0; k < system.num_joints(); ++k) loads.segment<2>(2 * k) = system.ConstraintLoad(k, t, y, lambda).f_W.head<2>();
    run.loads.push_back(loads);
  });
  return run;
}

// The largest difference of the bodies' origins [m] and Euler parameters (e and -e are the same
// rotation) between two states of the four-bar.
double PoseDifference(const MultibodySystem& system, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double difference = 0.0;
  for (int body = 0; body < system.num_bodies(); ++body) {
    const Eigen::Index p = system.position_offset(body);
    difference = std::max(difference, (a.segment<3>(p) - b.segment<3>(p)).norm());
    const Eigen::Vector4d e_a = a.segment<4>(p + 3), e_b = b.segment<4>(p + 3);
    difference = std::max(difference, std::min((e_a - e_b).norm(), (e_a + e_b).norm()));
  }
  return difference;
}

TEST(RedundantConstraints, PlanarFourBarDropsThreeRowsAndMovesLikeTheNonRedundantOne) {
  const FourBarGeometry geometry;
  FourBar redundant(geometry, JointType::kRevolute);
  FourBar reference(geometry, JointType::kSpherical);
  ASSERT_LE(MeasureConstraints(redundant.system, 0.0, redundant.y0).position, 1e-15);
  // Reference: 5 + 3 + 3 + 5 = 16 independent rows on 18 coordinates (the crank angle and the
  // coupler's idle spin).
  EXPECT_TRUE(FindRedundantConstraints(reference.system, 0.0, reference.y0, 1e-10).dropped_rows.empty());

  const double end_time = 2.0;  // about two swings
  const History run = Integrate(redundant.system, redundant.y0, end_time, 0.05);
  const History peer = Integrate(reference.system, reference.y0, end_time, 0.05);
  // The rows closing the loop out of its plane: the last joint's z coincidence and its two
  // axis alignments (stacked rows 17, 18, 19).
  const ConstraintRedundancy& dropped = run.statistics.initial_conditions.redundancy;
  EXPECT_EQ(dropped.dropped_rows, (std::vector<Eigen::Index>{17, 18, 19}));
  EXPECT_EQ(dropped.Describe(redundant.system),
            "3 rows dropped: 'rocker_ground' row 3 of 5, 'rocker_ground' row 4 of 5, 'rocker_ground' row 5 of 5");
  EXPECT_EQ(redundant.system.dropped_constraints(), dropped.dropped_rows);

  ASSERT_EQ(run.states.size(), peer.states.size());
  double motion = 0.0, loads = 0.0, swing = 0.0;
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    motion = std::max(motion, PoseDifference(redundant.system, run.states[k], peer.states[k]));
    loads = std::max(loads, (run.loads[k] - peer.loads[k]).cwiseAbs().maxCoeff());
    swing = std::max(swing, (run.states[k].segment<3>(0 + 7) - run.states[0].segment<3>(7)).norm());
  }
  std::printf("four-bar: max difference of poses %.3g, of in-plane joint forces %.3g N (coupler moved %.3g m)\n",
              motion, loads, swing);
  EXPECT_GT(swing, 0.1);  // it moved
  EXPECT_LT(motion, kSameMotion);
  EXPECT_LT(loads, kSameLoads);
}

TEST(RedundantConstraints, TwoLoopsDropSixRows) {
  // A Watt six-bar: the four-bar and a second loop from the rocker's middle C through coupler2
  // and rocker2 to the ground pivot F: 7 revolute joints, 35 rows on 30 coordinates, 1 DOF.
  const FourBarGeometry g;
  FourBar six(g, JointType::kRevolute);
  MultibodySystem& system = six.system;
  AddLink(system, "coupler2", 1.8);
  AddLink(system, "rocker2", 1.2);
  const Vector2d D(g.ground, 0.0), C = 0.5 * (D + six.B), F(3.5, 0.0);
  const Vector2d E = CircleIntersection(C, 1.8, F, 1.2);
  system.AddJoint(Joint("rocker_coupler2", JointType::kRevolute, system.Marker("rocker", "c"), system.Marker("coupler2", "a")));
  system.AddJoint(Joint("coupler2_rocker2", JointType::kRevolute, system.Marker("coupler2", "b"), system.Marker("rocker2", "b")));
  system.AddJoint(Joint("rocker2_ground", JointType::kRevolute, MarkerRef::Ground(Vector3d(F.x(), F.y(), 0.0)),
                        system.Marker("rocker2", "a")));
  Eigen::VectorXd y = system.NeutralState();
  y.head(21) = six.y0.head(21);  // the positions of the first three bodies (3 x 7)
  PlaceLink(system, 3, C, E, y);
  PlaceLink(system, 4, F, E, y);
  ASSERT_LE(MeasureConstraints(system, 0.0, y).position, 1e-14);
  const ConsistencyReport report = MakeConsistent(system, 0.0, y, ConsistencyOptions{});
  EXPECT_EQ(report.redundancy.dropped_rows, (std::vector<Eigen::Index>{17, 18, 19, 32, 33, 34}));
  // The kept rows are independent: 29 rows on 30 coordinates leave the one DOF.
  EXPECT_EQ(system.KeptConstraints().size(), 29u);
}

TEST(RedundantConstraints, DroppedRowThatStopsHoldingIsAChangeOfRedundancy) {
  // Dropping a row that is not redundant (the crank pivot's x coincidence of a four-bar closed
  // by spherical joints) leaves it to hold by itself; moved off it, the projection onto the kept
  // rows does not restore it, and the check names it.
  FourBar four_bar(FourBarGeometry{}, JointType::kSpherical);
  MultibodySystem& system = four_bar.system;
  ConstraintRedundancy redundancy;
  redundancy.dropped_rows = {0};
  redundancy.pivots = {0.0};
  redundancy.drift_rates = {0.0};
  system.set_dropped_constraints(redundancy.dropped_rows);
  const ProjectionOptions options;
  DroppedRowWatch watch(redundancy, kDroppedRowSlack * options.position_tolerance);
  Eigen::VectorXd y = four_bar.y0;
  watch.Check(system, 0.0, y);
  y.head(3) += Vector3d(1e-6, 0.0, 0.0);  // the crank's origin off the pivot along x
  try {
    ProjectPositions(system, 0.25, y, options);
    watch.Check(system, 0.25, y);
    ADD_FAILURE() << "no error";
  } catch (const SimulationError& error) {
    const std::string message = error.what();
    std::printf("%s\n", message.c_str());
    EXPECT_EQ(error.time(), 0.25);
    EXPECT_NE(message.find("the redundancy of the constraints changed"), std::string::npos);
    EXPECT_NE(message.find("'ground_crank' row 1 of 5"), std::string::npos);
  }
}

// The four-bar above (FourBarGeometry, AddLink's mass properties) as a scene: the plane x-y,
// gravity -y, released from rest at 60 degrees; the poses of B from CircleIntersection.
const char* kFourBarScene = R"(
gravity: [0, -9.81, 0]
bodies:
  crank:
    rigid: {mass: 1.0, center_of_mass: [0.5, 0, 0], inertia: [[1e-4, 0, 0], [0, 0.08333333333333333, 0], [0, 0, 0.08333333333333333]]}
    markers: {a: {position: [0, 0, 0]}, b: {position: [1, 0, 0]}}
    initial: {position: [0, 0, 0], rotation: {axis: [0, 0, 1], angle: 1.0471975511965976}}
  coupler:
    rigid: {mass: 2.2, center_of_mass: [1.1, 0, 0], inertia: [[2.2e-4, 0, 0], [0, 0.8873333333333334, 0], [0, 0, 0.8873333333333334]]}
    markers: {a: {position: [0, 0, 0]}, b: {position: [2.2, 0, 0]}}
    initial: {position: [0.5000000000000001, 0.8660254037844386, 0], rotation: {axis: [0, 0, 1], angle: 0.2237444074037527}}
  rocker:
    rigid: {mass: 1.5, center_of_mass: [0.75, 0, 0], inertia: [[1.5e-4, 0, 0], [0, 0.28125, 0], [0, 0, 0.28125]]}
    markers: {a: {position: [0, 0, 0]}, b: {position: [1.5, 0, 0]}}
    initial: {position: [2, 0, 0], rotation: {axis: [0, 0, 1], angle: 1.1261841938613348}}
joints:
  - {name: ground_crank, type: revolute, i: {body: ground}, j: {body: crank, marker: a}}
  - {name: crank_coupler, type: revolute, i: {body: crank, marker: b}, j: {body: coupler, marker: a}}
  - {name: coupler_rocker, type: revolute, i: {body: coupler, marker: b}, j: {body: rocker, marker: b}}
  - {name: rocker_ground, type: revolute, i: {body: ground, position: [2, 0, 0]}, j: {body: rocker, marker: a}}
simulation: {end_time: 1.0, output_interval: 0.01, relative_tolerance: 1e-12, absolute_tolerance: 1e-14}
)";

TEST(RedundantConstraints, CommandLineRunsAPlanarFourBarAndReportsTheDroppedRows) {
  ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
  const fs::path dir = fs::temp_directory_path() / ("flexmbs_redundant_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "four_bar.yaml") << kFourBarScene;
  const fs::path results = dir / "results.h5";
  const flexmbs::testing::Outcome run =
      flexmbs::testing::RunFlexmbs({"simulate", (dir / "four_bar.yaml").string(), "-o", results.string(), "--json"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["redundant_constraints"],
            nlohmann::json({"'rocker_ground' row 3 of 5", "'rocker_ground' row 4 of 5", "'rocker_ground' row 5 of 5"}));
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group provenance = root.OpenGroup("provenance");
  const std::vector<std::string> keys = provenance.ReadStrings("keys"), values = provenance.ReadStrings("values");
  const auto key = std::find(keys.begin(), keys.end(), "redundant_constraints");
  ASSERT_NE(key, keys.end());
  EXPECT_EQ(values[static_cast<std::size_t>(key - keys.begin())].rfind("3 rows dropped: 'rocker_ground' row 3 of 5", 0), 0u);
  // The same motion as the four-bar closed by spherical joints, run in the library.
  FourBar reference(FourBarGeometry{}, JointType::kSpherical);
  const History peer = Integrate(reference.system, reference.y0, 1.0, 0.01);
  const flexmbs::h5::Group bodies = root.OpenGroup("bodies");
  std::vector<Eigen::MatrixXd> positions, orientations;
  for (int b = 0; b < 3; ++b) {
    const flexmbs::h5::Group body = bodies.OpenGroup(reference.system.body(b).name());
    positions.push_back(body.ReadMatrix("position"));
    orientations.push_back(body.ReadMatrix("orientation"));
  }
  ASSERT_EQ(root.ReadVector("time").size(), static_cast<Eigen::Index>(peer.states.size()));
  double motion = 0.0;
  for (Eigen::Index k = 0; k < positions[0].rows(); ++k) {
    Eigen::VectorXd y = peer.states[static_cast<std::size_t>(k)];
    for (int b = 0; b < 3; ++b) {
      const Eigen::Index p = reference.system.position_offset(b);
      y.segment<3>(p) = positions[static_cast<std::size_t>(b)].row(k).transpose();
      y.segment<4>(p + 3) = orientations[static_cast<std::size_t>(b)].row(k).transpose();
    }
    motion = std::max(motion, PoseDifference(reference.system, y, peer.states[static_cast<std::size_t>(k)]));
  }
  std::printf("four-bar scene: max difference of poses from the library's non-redundant run %.3g\n", motion);
  EXPECT_LT(motion, kSameMotion);
  const Eigen::VectorXd energy = root.OpenGroup("energy").ReadVector("total");
  EXPECT_LT((energy.array() - energy(0)).abs().maxCoeff(), 1e-7);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace flexmbs::mbs
