// Planar scenes (mbs/planar.h, docs/mbs.md "Planar scenes"): a pendulum in planar mode against
// its exact period (elliptic integral), a chain of pendulums planar against the same chain run
// spatially (ODE methods, explicit and implicit with the sparse Newton solve) with the sizes of
// the solves and the CPU ratio printed, the constraint solver's G and M^-1 G^T over the kept
// columns only, and the load check's refusals of out-of-plane bodies.
#include "mbs/planar.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "mbs/constraint_solver.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "tests/input_error.h"
#include <unistd.h>

namespace flexmbs::mbs {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kG = 9.81, kMass = 1.0, kLength = 0.5;

/// A chain of `links` uniform rods (kMass, kLength along their x, origin at the proximal pin)
/// hanging by revolute joints about W z from the ground at W's origin, gravity -y, released at
/// rest straight out along `angle0` [rad] from W x.
struct Chain {
  std::unique_ptr<MultibodySystem> system;
  VectorXd y0;
  /// The rods' inertia about their centres: thin, with a small axial moment.
  static Matrix3d RodInertia() {
    return Vector3d(1e-4, kMass * kLength * kLength / 12.0, kMass * kLength * kLength / 12.0).asDiagonal();
  }
  /// Gravity g_W, the rods' centre of mass p_BoCm_B and inertia I_Cm_B may be changed (checks).
  Chain(int links, double angle0, const Vector3d& g_W = Vector3d(0.0, -kG, 0.0),
        const Vector3d& p_BoCm_B = Vector3d(kLength / 2.0, 0.0, 0.0), const Matrix3d& I_Cm_B = RodInertia()) {
    system = std::make_unique<MultibodySystem>(g_W);
    for (int k = 0; k < links; ++k) {
      const std::string name = "link" + std::to_string(k);
      system->AddBody(std::make_unique<RigidBody>(
          name, kMass, p_BoCm_B, I_Cm_B,
          std::vector<RigidBodyMarker>{{"pin", Vector3d::Zero(), Matrix3d::Identity()},
                                       {"tip", Vector3d(kLength, 0.0, 0.0), Matrix3d::Identity()}}));
      const MarkerRef parent = k == 0 ? MarkerRef::Ground(Vector3d::Zero())
                                      : system->Marker("link" + std::to_string(k - 1), "tip");
      system->AddJoint(Joint("pin" + std::to_string(k), JointType::kRevolute, parent, system->Marker(name, "pin")));
    }
    y0 = system->NeutralState();
    for (int k = 0; k < links; ++k) {
      VectorXd x(7);
      x << k * kLength * std::cos(angle0), k * kLength * std::sin(angle0), 0.0, std::cos(angle0 / 2.0), 0.0, 0.0,
          std::sin(angle0 / 2.0);
      system->SetBodyState(k, x, VectorXd::Zero(6), y0);
    }
  }
};

/// A run's end state, statistics and process CPU time.
struct ChainRun {
  VectorXd y_end;
  SimulationStatistics statistics;
  double cpu_seconds = 0.0;
};

ChainRun RunChain(Chain& chain, double end_time, const OdeOptions& integrator) {
  SimulationOptions options;
  options.end_time = end_time;
  options.output_interval = end_time;
  options.integrator = integrator;
  ChainRun run;
  const std::clock_t start = std::clock();
  run.statistics = Simulate(*chain.system, options, chain.y0,
                            [&](double, const VectorXd& y, const VectorXd&) { run.y_end = y; });
  run.cpu_seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  return run;
}

OdeOptions Tight(OdeMethod method, double tolerance) {
  OdeOptions options;
  options.method = method;
  options.relative_tolerance = tolerance;
  options.absolute_tolerance = tolerance;
  if (method == OdeMethod::kImplicit) options.newton = OdeNewton::kSparse;
  return options;
}

/// The largest difference of the in-plane coordinates and velocities of two states of a chain,
/// and the largest out-of-plane entry of either (p_z, e1, e2, v_z, w_x, w_y).
struct StateComparison {
  double in_plane = 0.0, out_of_plane = 0.0;
};
StateComparison Compare(const MultibodySystem& system, const VectorXd& a, const VectorXd& b) {
  StateComparison result;
  for (int k = 0; k < system.num_bodies(); ++k) {
    const Eigen::Index px = system.position_offset(k), pu = system.num_positions() + system.velocity_offset(k);
    for (const Eigen::Index i : {px, px + 1, px + 3, px + 6, pu, pu + 1, pu + 5}) {
      result.in_plane = std::max(result.in_plane, std::abs(a(i) - b(i)));
    }
    for (const Eigen::Index i : {px + 2, px + 4, px + 5, pu + 2, pu + 3, pu + 4}) {
      result.out_of_plane = std::max({result.out_of_plane, std::abs(a(i)), std::abs(b(i))});
    }
  }
  return result;
}

TEST(Planar, ConstraintSolverHoldsTheKeptColumnsOnly) {
  // A chain of 3 links turned to 0.4 rad, moving: G and M^-1 G^T of the solver against the dense
  // algebra over the kept columns s, G(:, s) and S M(s, s)^-1 S^T G^T, with no entry stored in a
  // dropped column.
  Chain chain(3, 0.4);
  MakePlanar(*chain.system, chain.y0);
  MultibodySystem& system = *chain.system;
  for (int k = 0; k < 3; ++k) chain.y0(system.num_positions() + system.velocity_offset(k) + 5) = 0.3 * (k + 1);
  const Eigen::MatrixXd G = system.Constraints(0.0, chain.y0).G;
  const ConstraintSolver solver(system, 0.0, chain.y0, G);
  std::vector<Eigen::Index> kept;
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Zero(system.num_velocities(), system.num_velocities());
  for (int b = 0; b < system.num_bodies(); ++b) {
    std::vector<Eigen::Index> s;
    for (const Eigen::Index column : system.KeptVelocities(b)) s.push_back(system.velocity_offset(b) + column);
    const Eigen::MatrixXd M_kept = system.BodyMassMatrix(b, chain.y0)(system.KeptVelocities(b), system.KeptVelocities(b));
    const Eigen::MatrixXd M_kept_inverse = M_kept.inverse();
    Minv(s, s) = M_kept_inverse;
    kept.insert(kept.end(), s.begin(), s.end());
  }
  Eigen::MatrixXd G_kept = Eigen::MatrixXd::Zero(G.rows(), G.cols());
  G_kept(Eigen::all, kept) = G(Eigen::all, kept);
  const Eigen::MatrixXd Minv_GT = Minv * G.transpose();
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& G_solver = solver.constraint_jacobian();
  for (Eigen::Index row = 0; row < G_solver.outerSize(); ++row) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(G_solver, row); it; ++it) {
      EXPECT_NE(std::find(kept.begin(), kept.end(), it.col()), kept.end()) << "row " << row << " column " << it.col();
    }
  }
  // The ground joint's 5 rows on its body's 3 kept columns, the other two joints' on two bodies' 6.
  EXPECT_EQ(G_solver.nonZeros(), 5 * 3 + 2 * 5 * 6);
  EXPECT_EQ((Eigen::MatrixXd(G_solver) - G_kept).cwiseAbs().maxCoeff(), 0.0);
  const double error = (Eigen::MatrixXd(solver.mass_inverse_G_transpose()) - Minv_GT).norm() / Minv_GT.norm();
  std::printf("planar solver: M^-1 G^T against the dense reduced algebra %.2e\n", error);
  // Measured: 4.9e-16.
  EXPECT_LT(error, 4e-15);
}

TEST(Planar, PendulumPeriodMatchesTheEllipticIntegral) {
  // Released horizontal: amplitude pi/2 from hanging. T = 4 K(sin(pi/4)) / omega0 with
  // omega0^2 = m g (L/2) / J_pin (Landau & Lifshitz, Mechanics, sec. 11).
  Chain chain(1, 0.0), spatial(1, 0.0);
  MakePlanar(*chain.system, chain.y0);
  const double J_pin = kMass * kLength * kLength / 3.0;
  const double omega0 = std::sqrt(kMass * kG * kLength / 2.0 / J_pin);
  const double period = 4.0 * std::comp_ellint_1(std::sin(std::numbers::pi / 4.0)) / omega0;
  const ChainRun run = RunChain(chain, period, Tight(OdeMethod::kExplicit, 1e-12));
  const ChainRun spatial_run = RunChain(spatial, period, Tight(OdeMethod::kExplicit, 1e-12));
  const StateComparison comparison = Compare(*chain.system, run.y_end, spatial_run.y_end);
  // Back at the turning point: the rate left is the period error times the angular acceleration
  // there, omega0^2 sin(pi/2).
  const double w_z = run.y_end(7 + 5);
  const double period_error = std::abs(w_z) / (omega0 * omega0) / period;
  const double angle = 2.0 * std::atan2(run.y_end(6), run.y_end(3));
  std::printf("planar pendulum: T = %.12f s, relative period error %.2e, angle error %.2e rad, %zu rows dropped; "
              "against the spatial run: in-plane %.2e, out-of-plane %.2e\n",
              period, period_error, angle, run.statistics.initial_conditions.redundancy.dropped_rows.size(),
              comparison.in_plane, comparison.out_of_plane);
  // Measured 1.9e-12 (period, relative) and 1.7e-11 rad (angle).
  EXPECT_LT(period_error, 2e-11);
  EXPECT_LT(std::abs(angle), 2e-10);
  // The spatial run of the same scene: the same steps, to round-off (measured 9.5e-14).
  EXPECT_EQ(comparison.out_of_plane, 0.0);
  EXPECT_LT(comparison.in_plane, 1e-12);
  // The revolute's z translation and x, y alignments are zero rows of G S: dropped at t0.
  EXPECT_EQ(run.statistics.initial_conditions.redundancy.dropped_rows, (std::vector<Eigen::Index>{2, 3, 4}));
}

/// Runs a chain of 10 links planar and spatially with `integrator`; returns the comparison and
/// prints the solves' sizes and the CPU ratio.
StateComparison PlanarAgainstSpatial(const OdeOptions& integrator, const char* label) {
  constexpr int kLinks = 10;
  constexpr double kEndTime = 1.0;
  Chain spatial(kLinks, 0.3), planar(kLinks, 0.3);
  MakePlanar(*planar.system, planar.y0);
  const ChainRun a = RunChain(spatial, kEndTime, integrator);
  const ChainRun b = RunChain(planar, kEndTime, integrator);
  const StateComparison comparison = Compare(*spatial.system, a.y_end, b.y_end);
  const std::size_t spatial_rows = spatial.system->KeptConstraints().size();
  const std::size_t planar_rows = planar.system->KeptConstraints().size();
  std::printf("%s, %d links, %.1f s: velocities %zu -> %zu, constraint rows %zu -> %zu (saddle point %zu -> %zu); steps %ld / %ld; "
              "in-plane difference %.2e, out-of-plane %.2e; CPU spatial %.3f s, planar %.3f s (ratio %.2f)\n",
              label, kLinks, kEndTime, spatial.system->KeptVelocities().size(), planar.system->KeptVelocities().size(),
              spatial_rows, planar_rows, spatial.system->KeptVelocities().size() + spatial_rows,
              planar.system->KeptVelocities().size() + planar_rows, a.statistics.integrator.steps,
              b.statistics.integrator.steps, comparison.in_plane, comparison.out_of_plane, a.cpu_seconds, b.cpu_seconds,
              a.cpu_seconds / b.cpu_seconds);
  EXPECT_EQ(spatial_rows, 5u * kLinks);
  EXPECT_EQ(planar_rows, 2u * kLinks);
  EXPECT_EQ(planar.system->KeptVelocities().size(), 3u * kLinks);
  return comparison;
}

TEST(Planar, ChainAgreesWithTheSpatialRunExplicit) {
  const StateComparison c = PlanarAgainstSpatial(Tight(OdeMethod::kExplicit, 1e-10), "explicit");
  // The same motion: out-of-plane entries stay exact zeros in both runs; in-plane the runs (the
  // same 544 steps) differ by the round-off of their different solves, grown by the chain's
  // motion over 1 s: measured 2.6e-11.
  EXPECT_EQ(c.out_of_plane, 0.0);
  EXPECT_LT(c.in_plane, 3e-10);
}

TEST(Planar, ChainAgreesWithTheSpatialRunImplicitSparseNewton) {
  // The sparse Newton matrix keeps its n_u + m rows, the dropped velocities' as identity rows
  // (kkt_newton_solver.h). Measured: the same 1285 steps, in-plane difference 1.2e-11.
  const StateComparison c = PlanarAgainstSpatial(Tight(OdeMethod::kImplicit, 1e-8), "implicit, sparse Newton");
  EXPECT_EQ(c.out_of_plane, 0.0);
  EXPECT_LT(c.in_plane, 1.5e-10);
}

// ---------------------------------------------------------------------------------------------
// The load check (library level) and the scene key.

std::string Refusal(Chain& chain) {
  return flexmbs::testing::InputErrorMessage([&] { MakePlanar(*chain.system, chain.y0); });
}

/// `message` begins with `prefix` (the values after it are the solver's).
bool StartsWith(const std::string& message, const std::string& prefix) { return message.rfind(prefix, 0) == 0; }

TEST(PlanarCheck, OutOfPlaneInitialStatesAreRefused) {
  {
    Chain chain(2, 0.3);
    chain.y0(chain.system->num_positions() + chain.system->velocity_offset(1) + 2) = 0.25;  // v_z
    EXPECT_EQ(Refusal(chain), "body 'link1': initial v_z = 0.25 is out of the plane");
  }
  {
    Chain chain(2, 0.3);
    chain.y0(chain.system->num_positions() + 3) = -0.5;  // w_x of link0
    EXPECT_EQ(Refusal(chain), "body 'link0': initial w_B_x = -0.5 is out of the plane");
  }
  {
    Chain chain(1, 0.0);
    chain.y0(2) = 0.1;  // p_z
    EXPECT_EQ(Refusal(chain), "body 'link0': initial centre of mass (0.25, 0, 0.1) m is off the plane z = 0");
  }
  {
    Chain chain(1, 0.0);
    chain.y0.segment<4>(3) << std::cos(0.1), std::sin(0.1), 0.0, 0.0;  // 0.2 rad about W x
    EXPECT_EQ(Refusal(chain), "body 'link0': initial rotation's Euler parameters (0.995004, 0.0998334, 0, 0) "
                              "turn about an axis out of z");
  }
}

TEST(PlanarCheck, GravityAndMassCouplingOutOfThePlaneAreRefused) {
  {
    Chain chain(1, 0.0, Vector3d(0.0, -kG, -0.5));
    EXPECT_EQ(Refusal(chain), "gravity: (0, -9.81, -0.5) m/s^2 has the out-of-plane component -0.5");
  }
  {
    // The centre of mass 0.1 m off the body's xy plane, the body 0.1 m below W's: in the plane,
    // but its mass matrix couples v_y and w_x (M = -m c_z).
    Chain chain(1, 0.0, Vector3d(0.0, -kG, 0.0), Vector3d(kLength / 2.0, 0.0, 0.1));
    chain.y0(2) = -0.1;
    EXPECT_TRUE(StartsWith(Refusal(chain), "body 'link0': its mass matrix couples the in-plane v_y with the "
                                           "out-of-plane w_B_x: M = -0.1 ("))
        << Refusal(chain);
  }
  {
    Matrix3d inertia = Chain::RodInertia();
    inertia(0, 2) = inertia(2, 0) = 1e-3;  // J_xz
    Chain chain(1, 0.0, Vector3d(0.0, -kG, 0.0), Vector3d(kLength / 2.0, 0.0, 0.0), inertia);
    EXPECT_TRUE(StartsWith(Refusal(chain), "body 'link0': its mass matrix couples the in-plane w_B_z with the "
                                           "out-of-plane w_B_x: M = 0.001 ("))
        << Refusal(chain);
  }
}

TEST(PlanarCheck, JointAxesOutOfThePlaneAreRefused) {
  const Matrix3d about_x = Eigen::AngleAxisd(std::numbers::pi / 2.0, Vector3d::UnitX()).toRotationMatrix();
  const Matrix3d about_y = Eigen::AngleAxisd(std::numbers::pi / 2.0, Vector3d::UnitY()).toRotationMatrix();
  const auto refusal = [&](JointType type, const Matrix3d& R_axis) {
    Chain chain(1, 0.0);
    MultibodySystem& system = *chain.system;
    system.AddBody(std::make_unique<RigidBody>("slider", kMass, Vector3d::Zero(), Chain::RodInertia(),
                                               std::vector<RigidBodyMarker>{{"rail", Vector3d::Zero(), R_axis}}));
    system.AddJoint(Joint("guide", type, MarkerRef::Ground(Vector3d::Zero(), R_axis), system.Marker("slider", "rail")));
    chain.y0 = system.NeutralState();
    return Refusal(chain);
  };
  // A prismatic joint along W x (its axis, I's z, turned onto x) and a revolute about W z pass.
  EXPECT_EQ(refusal(JointType::kPrismatic, about_y), "no error");
  EXPECT_EQ(refusal(JointType::kRevolute, Matrix3d::Identity()), "no error");
  EXPECT_EQ(refusal(JointType::kRevolute, about_x), "joint 'guide' (revolute): axis (0, -1, 6.12323e-17) must be z");
  EXPECT_EQ(refusal(JointType::kPrismatic, Matrix3d::Identity()),
            "joint 'guide' (prismatic): axis (0, 0, 1) must lie in the plane xy");
  EXPECT_EQ(refusal(JointType::kCylindrical, Eigen::AngleAxisd(0.3, Vector3d::UnitX()).toRotationMatrix()),
            "joint 'guide' (cylindrical): axis (0, -0.29552, 0.955336) must be z or lie in the plane xy");
  EXPECT_EQ(refusal(JointType::kUniversal, Matrix3d::Identity()),
            "joint 'guide' (universal): a universal joint has no planar form (a revolute about z)");
}

const char* kPendulumScene = R"(planar: xy
gravity: [0, -9.81, 0]
bodies:
  rod:
    rigid: {mass: 1, center_of_mass: [0.25, 0, 0], inertia: [[1e-4, 0, 0], [0, 0.0208, 0], [0, 0, 0.0208]]}
    markers: {pin: {position: [0, 0, 0]}}
    initial: {rotation: {axis: [0, 0, 1], angle: 0.3}, angular_velocity: [0, 0, 1]}
joints:
  - {name: pin, type: revolute, i: {body: ground, position: [0, 0, 0]}, j: {body: rod, marker: pin}}
simulation: {end_time: 0.1}
)";

/// The error of loading kPendulumScene with `from` replaced by `to`, or "no error".
std::string SceneRefusal(const std::string& from, const std::string& to) {
  std::string text = kPendulumScene;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("flexmbs_planar_scene_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << text;
  const std::string message = flexmbs::testing::InputErrorMessage([&] { LoadScene(file); });
  std::filesystem::remove(file);
  return message;
}

/// `message` ends with `suffix`.
bool EndsWith(const std::string& message, const std::string& suffix) {
  return message.size() >= suffix.size() && message.compare(message.size() - suffix.size(), suffix.size(), suffix) == 0;
}

TEST(PlanarScene, TheKeyMakesTheSystemPlanarAndRefusesOutOfPlaneItemsAtItsLine) {
  EXPECT_EQ(SceneRefusal("planar: xy", "planar: xy"), "no error");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("flexmbs_planar_scene_ok_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << kPendulumScene;
  const Scene scene = LoadScene(file);
  std::filesystem::remove(file);
  EXPECT_TRUE(scene.system->planar());
  EXPECT_EQ(scene.system->KeptVelocities(), (std::vector<Eigen::Index>{0, 1, 5}));
  // Each refusal is one line at the key planar (line 1, column 9) naming the item and value.
  const std::string at_key = ":1:9: ";
  std::string m = SceneRefusal("planar: xy", "planar: xz");
  EXPECT_TRUE(EndsWith(m, ":1:9: planar: 'xz': the planar scenes' plane is xy")) << m;
  m = SceneRefusal("gravity: [0, -9.81, 0]", "gravity: [0, 0, -9.81]");
  EXPECT_TRUE(EndsWith(m, at_key + "planar: gravity: (0, 0, -9.81) m/s^2 has the out-of-plane component -9.81")) << m;
  m = SceneRefusal("angular_velocity: [0, 0, 1]", "angular_velocity: [0.5, 0, 1]");
  EXPECT_TRUE(EndsWith(m, at_key + "planar: body 'rod': initial w_B_x = 0.477668 is out of the plane")) << m;
  m = SceneRefusal("angle: 0.3}, angular", "angle: 0.3}, velocity: [0, 0, 2], angular");
  EXPECT_TRUE(EndsWith(m, at_key + "planar: body 'rod': initial v_z = 2 is out of the plane")) << m;
  m = SceneRefusal("axis: [0, 0, 1], angle: 0.3", "axis: [0, 1, 1], angle: 0.3");
  EXPECT_NE(m.find(at_key + "planar: body 'rod': initial rotation's Euler parameters"), std::string::npos) << m;
  m = SceneRefusal("{body: ground, position: [0, 0, 0]}", "{body: ground, position: [0, 0, 0], rotation: {axis: [0, 1, 0], angle: 0.5}}");
  EXPECT_TRUE(EndsWith(m, at_key + "planar: joint 'pin' (revolute): axis (0.479426, 0, 0.877583) must be z")) << m;
  // (0.25 cos 0.3, 0.25 sin 0.3, 0.01): the centre of mass turned with the body.
  m = SceneRefusal("center_of_mass: [0.25, 0, 0]", "center_of_mass: [0.25, 0, 0.01]");
  EXPECT_TRUE(EndsWith(m, at_key + "planar: body 'rod': initial centre of mass (0.238834, 0.0738801, 0.01) m is off the plane z = 0")) << m;
}

}  // namespace
}  // namespace flexmbs::mbs
