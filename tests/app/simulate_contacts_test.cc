// `flexmbs simulate` with unilateral contacts (docs/scene.md, "Unilateral contacts"): the
// scene of that section, read from the page, runs by Moreau-Jean time stepping into a results
// file whose contact datasets hold the closed-form bounce; a unilateral contact under an ODE
// method is refused with one line and exit 2; a reduced cube lands on its bottom contact surface
// (surface_plane), and a surface contact naming a rigid body or a missing surface is refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/h5_file.h"
#include "tests/app/contact_scenes.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;

using flexmbs::testing::SceneOfSection;

class SimulateContactsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    dir_ = fs::temp_directory_path() / ("flexmbs_simulate_contacts_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  Outcome Simulate(const std::string& scene, bool json = false) {
    std::ofstream(dir_ / "scene.yaml") << scene;
    results_ = dir_ / "results.h5";
    std::vector<std::string> args{"simulate", (dir_ / "scene.yaml").string(), "-o", results_.string()};
    if (json) args.push_back("--json");
    return flexmbs::testing::RunFlexmbs(args, dir_);
  }
  fs::path dir_, results_;
};

TEST_F(SimulateContactsTest, TheDocumentedBouncingBallRunsAndRecordsItsImpacts) {
  const std::string scene = SceneOfSection("## Unilateral contacts (`contacts:`)");
  ASSERT_NE(scene.find("method: moreau_jean"), std::string::npos) << "the example is gone from docs/scene.md";
  const Outcome run = Simulate(scene, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["steps"], 400);  // 2 s / 0.005 s
  EXPECT_EQ(report["max_active_contacts"], 1);
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group floor = root.OpenGroup("contacts").OpenGroup("floor");
  EXPECT_EQ(floor.GetStringAttribute("type"), "sphere_plane");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = floor.ReadVector("gap");
  const Eigen::VectorXd impulse = floor.ReadVector("normal_impulse"), active = floor.ReadVector("active");
  ASSERT_EQ(time.size(), 201);
  ASSERT_EQ(gap.size(), 201);
  EXPECT_EQ(floor.ReadMatrix("tangential_impulse").cols(), 2);
  EXPECT_NEAR(gap(0), 1.0, 1e-15);
  // The first impact, at sqrt(2 h0 / g) = 0.4515 s, lies in the step ending at 0.455 s, in the
  // output interval ending at 0.46 s; the ball rebounds with e v_1 = 0.9 sqrt(2 g h0): the
  // interval's impulse is (1 + e) m v_1 up to the weight's impulse over the interval.
  Eigen::Index first = 0;
  while (first < impulse.size() && impulse(first) == 0.0) ++first;
  ASSERT_LT(first, impulse.size());
  EXPECT_EQ(active(first), 1.0);
  EXPECT_NEAR(time(first), std::sqrt(2.0 / 9.81), 0.01);
  EXPECT_NEAR(impulse(first), 1.9 * std::sqrt(2.0 * 9.81), 9.81 * 0.01);
  EXPECT_EQ((impulse.array() > 0.0).count(), 2);  // impacts in the steps ending at 0.455 and 1.270 s (the
                                                  // third ends at 2.005 s, as in Siconos)
  EXPECT_NEAR(impulse.sum(), 1.9 * std::sqrt(2.0 * 9.81) * (1.0 + 0.9), 2.0 * 9.81 * 0.01);
}

// statistics/contact_solve_cpu_seconds of docs/scene.md's two bouncing balls (Moreau-Jean,
// event-driven): measured, positive, a share of the integration's CPU time, and the JSON report's.
TEST_F(SimulateContactsTest, ContactSolvesAreAShareOfTheIntegrationsCpuTime) {
  for (const std::string heading : {"## Unilateral contacts (`contacts:`)", "### `method: event_driven`"}) {
    const std::string scene = SceneOfSection(heading);
    ASSERT_FALSE(scene.empty()) << heading;
    const Outcome run = Simulate(scene, true);
    ASSERT_EQ(run.exit_code, 0) << heading << ": " << run.err;
    const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
    const flexmbs::h5::Group statistics = file.root().OpenGroup("statistics");
    const double contact = statistics.ReadScalar("contact_solve_cpu_seconds");
    EXPECT_EQ(nlohmann::json::parse(run.out)["contact_solve_cpu_seconds"].get<double>(), contact) << heading;
    const double integration = statistics.ReadVector("cpu_seconds")(1);
    std::printf("%s: contact solves %.3g s of the integration's %.3g s CPU\n", heading.c_str(), contact, integration);
    EXPECT_EQ(statistics.ReadUnits("contact_solve_cpu_seconds"), "s");
    EXPECT_GT(contact, 0.0) << heading;  // both runs have impacts; NaN fails too
    EXPECT_LE(contact, integration) << heading;
  }
}

TEST_F(SimulateContactsTest, UnilateralContactUnderAnOdeMethodIsRefused) {
  std::string scene = SceneOfSection("## Unilateral contacts (`contacts:`)");
  scene.replace(scene.find("method: moreau_jean"), 19, "method: implicit   ");
  scene.replace(scene.find("  step: 0.005"), 13, "  # step gone");
  scene.replace(scene.find("  theta: 0.5"), 12, "  # no theta");
  scene.replace(scene.find("  impact_level:"), 15, "  # no level:  ");
  flexmbs::testing::ExpectInputError(Simulate(scene), "contacts[0]: contact 'floor' is unilateral");
  EXPECT_FALSE(fs::exists(results_));
}

/// Reduces the cube with two free-free modes and the contact surface "bottom" (z = 0) in `dir`.
void ReduceCubeWithBottomSurface(const fs::path& dir) {
  const Outcome reduce = flexmbs::testing::ReduceCube(dir, "method: free_free, modes: 2", "bottom");
  ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
}

/// A flexible cube whose bottom face starts 1 mm above the ground, against it by surface_plane.
const char* kDroppedCube = R"(gravity: [0, 0, -9.81]
bodies:
  cube:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
    initial: {position: [0, 0, 0.001]}
contacts:
  - {name: floor, type: surface_plane, body: cube, surface: bottom, plane: {body: ground}}
simulation: {end_time: 0.05, output_interval: 0.001, method: moreau_jean, step: 1e-4}
)";

TEST_F(SimulateContactsTest, FlexibleCubeLandsOnItsBottomSurfaceAndRests) {
  ReduceCubeWithBottomSurface(dir_);
  if (HasFatalFailure()) return;
  const Outcome run = Simulate(kDroppedCube, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_GT(report["max_active_contacts"].get<int>(), 2);  // the face's vertices, not one point
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group floor = root.OpenGroup("contacts").OpenGroup("floor");
  EXPECT_EQ(floor.GetStringAttribute("type"), "surface_plane");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = floor.ReadVector("gap");
  const Eigen::VectorXd impulse = floor.ReadVector("normal_impulse");
  EXPECT_NEAR(gap(0), 0.001, 1e-15);
  // Free fall to the touch at sqrt(2 g0 / g) = 14.3 ms: no impulse in the intervals before it.
  for (Eigen::Index k = 0; k < time.size() && time(k) < 0.014; ++k) EXPECT_EQ(impulse(k), 0.0) << time(k);
  // From rest to rest (e = 0; the two modes' vibration carries no momentum): the floor's impulse
  // over the run is the weight's, m g T, up to the cube's final speed.
  const double mass = 7850.0 * 1e-3;
  const Eigen::MatrixXd velocity = root.OpenGroup("bodies").OpenGroup("cube").ReadMatrix("velocity");
  EXPECT_NEAR(impulse.sum() + mass * velocity(velocity.rows() - 1, 2), mass * 9.81 * time(time.size() - 1), 1e-9);
  EXPECT_LT(std::abs(velocity(velocity.rows() - 1, 2)), 1e-3);
  EXPECT_LT(std::abs(gap(gap.size() - 1)), 1e-4);  // resting on the floor
}

TEST_F(SimulateContactsTest, SurfaceContactOnARigidBodyOrAMissingSurfaceIsRefused) {
  ReduceCubeWithBottomSurface(dir_);
  if (HasFatalFailure()) return;
  std::string scene = kDroppedCube;
  scene.replace(scene.find("surface: bottom"), 15, "surface: top   ");
  flexmbs::testing::ExpectInputError(Simulate(scene),
                                     "contacts[0].surface: contact 'floor': body 'cube' carries no contact surface "
                                     "'top' (it has: bottom)");
  EXPECT_FALSE(fs::exists(results_));
  scene = kDroppedCube;
  scene.replace(scene.find("body: cube,"), 11, "body: cubes,");
  flexmbs::testing::ExpectInputError(Simulate(scene), "contacts[0].body: contact 'floor': no body 'cubes'");
  const std::string rigid = std::string(kDroppedCube).replace(
      std::string(kDroppedCube).find("    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}"), 59,
      "    rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}");
  flexmbs::testing::ExpectInputError(Simulate(rigid),
                                     "contacts[0].body: contact 'floor': body 'cube' is rigid; surfaces are a flexible "
                                     "body's");
}

/// Two flexible cubes (the cube reduced with two free-free modes and the surfaces "bottom" and
/// "top") without gravity: the upper one 1 mm above the lower one, moving down at 1 m/s onto it,
/// by surface_surface (its bottom face's vertices against the lower one's top face).
const char* kCubeOnCube = R"(gravity: [0, 0, 0]
bodies:
  lower:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
  upper:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
    initial: {position: [0, 0, 0.101], velocity: [0, 0, -1]}
contacts:
  - {name: stack, type: surface_surface, surface1: {body: upper, surface: bottom}, surface2: {body: lower, surface: top}}
simulation: {end_time: 0.004, output_interval: 1e-4, method: moreau_jean, step: 1e-5}
)";

TEST_F(SimulateContactsTest, FlexibleCubeStrikesAFlexibleCubeFaceOnFace) {
  const Outcome reduce = flexmbs::testing::ReduceCube(dir_, "method: free_free, modes: 2", "bottom, top");
  ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
  const Outcome run = Simulate(kCubeOnCube, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  const flexmbs::h5::Group stack = root.OpenGroup("contacts").OpenGroup("stack");
  EXPECT_EQ(stack.GetStringAttribute("type"), "surface_surface");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = stack.ReadVector("gap");
  const Eigen::VectorXd impulse = stack.ReadVector("normal_impulse");
  EXPECT_NEAR(gap(0), 0.001, 1e-12);
  // No impulse before the touch at 1 ms; the impulses act equal and opposite: the momentum m v
  // is kept, and e = 0 at the points makes the impact plastic (two modes that carry no momentum):
  // both cubes end near v / 2, the lower one pushed by the whole impulse.
  for (Eigen::Index k = 0; k < time.size() && time(k) < 0.99e-3; ++k) EXPECT_EQ(impulse(k), 0.0) << time(k);
  const double mass = 7850.0 * 1e-3;
  const flexmbs::h5::Group bodies = root.OpenGroup("bodies");
  const Eigen::MatrixXd upper = bodies.OpenGroup("upper").ReadMatrix("velocity");
  const Eigen::MatrixXd lower = bodies.OpenGroup("lower").ReadMatrix("velocity");
  const double v_upper = upper(upper.rows() - 1, 2), v_lower = lower(lower.rows() - 1, 2);
  std::printf("cube on cube: upper %.9f m/s, lower %.9f m/s (v / 2 %+.3e), impulse %.6g N s (m v / 2 = %.6g)\n",
              v_upper, v_lower, v_lower + 0.5, impulse.sum(), 0.5 * mass);
  EXPECT_NEAR(v_upper + v_lower, -1.0, 1e-9);
  EXPECT_NEAR(mass * v_lower, -impulse.sum(), 1e-9);
  EXPECT_NEAR(v_lower, -0.5, 1e-13);  // measured 1.0e-15: they move on together
  // A surface the lower cube does not carry is named with those it has.
  std::string scene = kCubeOnCube;
  scene.replace(scene.find("surface2: {body: lower, surface: top}"), 37, "surface2: {body: lower, surface: side}");
  flexmbs::testing::ExpectInputError(Simulate(scene),
                                     "contacts[0].surface2.surface: contact 'stack': body 'lower' carries no contact "
                                     "surface 'side' (it has: bottom, top)");
}

/// The same cubes under gravity, the lower one on the ground (surface_plane), the upper one 1 mm
/// above it: 94 contact points on 16 velocities once they rest (docs/contact.md, "surface_surface").
const char* kStackedCubes = R"(gravity: [0, 0, -9.81]
bodies:
  lower:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
  upper:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
    initial: {position: [0, 0, 0.101]}
contacts:
  - {name: floor, type: surface_plane, body: lower, surface: bottom, plane: {body: ground}}
  - {name: stack, type: surface_surface, surface1: {body: upper, surface: bottom}, surface2: {body: lower, surface: top}}
simulation: {end_time: 0.05, output_interval: 0.001, method: moreau_jean, step: 1e-4}
)";

TEST_F(SimulateContactsTest, FlexibleCubeLandsOnAFlexibleCubeAndTheStackRests) {
  const Outcome reduce = flexmbs::testing::ReduceCube(dir_, "method: free_free, modes: 2", "bottom, top");
  ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
  const Outcome run = Simulate(kStackedCubes, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_LE(report["max_contact_solver_error"].get<double>(), 1e-10);
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root(), contacts = root.OpenGroup("contacts");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = contacts.OpenGroup("stack").ReadVector("gap");
  const Eigen::VectorXd stack = contacts.OpenGroup("stack").ReadVector("normal_impulse");
  const Eigen::VectorXd floor = contacts.OpenGroup("floor").ReadVector("normal_impulse");
  // Free fall to the touch at 14.3 ms; then each body's momentum balance: the stack carries the
  // upper cube's weight over the run up to its final momentum, the floor both cubes' (e = 0; the
  // modes carry no momentum).
  for (Eigen::Index k = 0; k < time.size() && time(k) < 0.014; ++k) EXPECT_EQ(stack(k), 0.0) << time(k);
  const double mass = 7850.0 * 1e-3, T = time(time.size() - 1);
  const flexmbs::h5::Group bodies = root.OpenGroup("bodies");
  const Eigen::MatrixXd upper = bodies.OpenGroup("upper").ReadMatrix("velocity");
  const Eigen::MatrixXd lower = bodies.OpenGroup("lower").ReadMatrix("velocity");
  const double v_upper = upper(upper.rows() - 1, 2), v_lower = lower(lower.rows() - 1, 2);
  const double upper_balance = stack.sum() + mass * v_upper - mass * 9.81 * T;
  const double floor_balance = floor.sum() + mass * (v_upper + v_lower) - 2.0 * mass * 9.81 * T;
  std::printf("stacked cubes at %g s: upper %.3e m/s, lower %.3e m/s, gap %.3e m; momentum balances %.3e, %.3e N s\n",
              T, v_upper, v_lower, gap(gap.size() - 1), upper_balance, floor_balance);
  // Measured: balances 2.8e-14 and 1.5e-13 N s (round-off of 500 summed impulses of ~4e-3 N s);
  // speeds 1.1e-18, 2.2e-18 m/s; the gap -1.0e-5 m (the landing step's penetration, kept on
  // velocity level).
  EXPECT_LT(std::abs(upper_balance), 1e-12);
  EXPECT_LT(std::abs(floor_balance), 1e-12);
  EXPECT_LT(std::abs(v_upper) + std::abs(v_lower), 1e-15);
  EXPECT_LT(std::abs(gap(gap.size() - 1)), 1e-4);
}

/// Reduces the cube with six free-free modes, the contact surface "top" (z = 0.1 m) and `extra`
/// reduction keys in `dir`.
void ReduceCubeWithTopSurface(const fs::path& dir, const std::string& extra) {
  const Outcome reduce = flexmbs::testing::ReduceCube(dir, "method: free_free, modes: 6" + extra, "top");
  ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
}

/// A steel ball (r = 5 mm) 1 um above the centre of the cube's top face, falling on it at 1 m/s,
/// through a Hertz sphere_surface_contact; no gravity.
const char* kBallOnCube = R"(gravity: [0, 0, 0]
bodies:
  cube:
    flexible: {file: cube.sid.h5}
  ball:
    rigid: {mass: 0.0041097, inertia: [[4.1097e-8, 0, 0], [0, 4.1097e-8, 0], [0, 0, 4.1097e-8]]}
    markers: {centre: {position: [0, 0, 0]}}
    initial: {position: [0.05, 0.05, 0.105001], velocity: [0, 0, -1]}
forces:
  - name: hit
    type: sphere_surface_contact
    sphere: {body: ball, marker: centre}
    radius: 0.005
    body: cube
    surface: top
    law: hertz
    materials:
      sphere: {youngs_modulus: 2.1e11, poissons_ratio: 0.3}
      surface: {youngs_modulus: 2.1e11, poissons_ratio: 0.3}
simulation:
  {end_time: 6e-5, output_interval: 1e-6, method: implicit, relative_tolerance: 1e-8, absolute_tolerance: 1e-14}
)";

TEST_F(SimulateContactsTest, SphereOnAFlexibleSurfaceBouncesAndGetsModeAdvice) {
  // Hertz (Johnson 1985, §11.4) for the ball on the cube's face: E* = E / (2 (1 - nu^2)),
  // k = 4/3 E* sqrt(r), m* = m_ball m_cube / (m_ball + m_cube) (the ball over the cube's centre of
  // mass), t_c = 2.9433 (5 m* v^2 / (4 k))^(2/5) / v (Johnson's 2.94 to five digits: 2 int_0^1
  // dx / sqrt(1 - x^(5/2)) by scipy.integrate.quad).
  const double k = 4.0 / 3.0 * 2.1e11 / (2.0 * (1.0 - 0.09)) * std::sqrt(0.005);
  const double m_ball = 0.0041097, m_cube = 7850.0 * 1e-3, mass = m_ball * m_cube / (m_ball + m_cube);
  const double t_c = 2.943275184324214 * std::pow(5.0 * mass / (4.0 * k), 0.4);
  for (const bool correction : {false, true}) {
    SCOPED_TRACE(correction);
    ReduceCubeWithTopSurface(dir_, correction ? ", correction_modes: [{node_set: top, direction: [0, 0, 1]}]" : "");
    if (HasFatalFailure()) return;
    const Outcome run = Simulate(kBallOnCube, true);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["mode_advice"].size(), 1u) << run.out;
    const nlohmann::json& advice = report["mode_advice"][0];
    EXPECT_EQ(advice["element"], "hit");
    EXPECT_EQ(advice["body"], "cube");
    EXPECT_EQ(advice["type"], "sphere_surface_contact");
    EXPECT_EQ(advice["first_points"].get<int>(), 1);
    EXPECT_NEAR(advice["effective_mass_kg"].get<double>(), mass, 1e-12 * mass);
    EXPECT_NEAR(advice["impact_speed_m_s"].get<double>(), 1.0, 1e-12);
    EXPECT_NEAR(advice["contact_time_s"].get<double>(), t_c, 1e-9 * t_c);
    EXPECT_NEAR(advice["law_stiffness"].get<double>(), k, 1e-12 * k);  // the scene's Hertz law by the same formula: round-off
    EXPECT_EQ(advice["law_exponent"].get<double>(), 1.5);
    EXPECT_EQ(advice["correction_mode"].get<bool>(), correction);
    EXPECT_NEAR(advice["cutoff_hz"].get<double>(), (correction ? 1.5 : 3.0) / t_c, 1e-6 / t_c);
    const int loaded = advice["loaded_modes"].get<int>();
    EXPECT_GE(loaded, 1);
    EXPECT_LE(loaded, correction ? 7 : 6);
    EXPECT_LE(advice["loaded_modes_above_cutoff"].get<int>(), loaded);
    // The ball bounces off: it touches after 1 um / (1 m/s) = 1 us and leaves after about t_c
    // (35 us), within the run.
    const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
    const Eigen::MatrixXd velocity =
        file.root().OpenGroup("bodies").OpenGroup("ball").ReadMatrix("velocity");
    EXPECT_GT(velocity(velocity.rows() - 1, 2), 0.5);
  }
  const Outcome text = Simulate(kBallOnCube);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("modes           contact 'hit' (sphere_surface_contact) on cube: contact time"), std::string::npos) << text.out;
}

TEST_F(SimulateContactsTest, BadCompliantSurfaceContactsAreOneLocatedLine) {
  ReduceCubeWithTopSurface(dir_, "");
  if (HasFatalFailure()) return;
  const std::string scene = kBallOnCube;
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = scene;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  flexmbs::testing::ExpectInputError(Simulate(with("    radius: 0.005", "    radius: -0.005")),
                                     "forces[0].radius: force element 'hit': -0.005 m must be > 0");
  EXPECT_FALSE(fs::exists(results_));
  flexmbs::testing::ExpectInputError(
      Simulate(with("    body: cube\n", "    body: ball\n")),
      "forces[0].body: force element 'hit': body 'ball' is rigid; surfaces are a flexible body's");
  flexmbs::testing::ExpectInputError(Simulate(with("    surface: top", "    surface: side")),
                                     "forces[0].surface: force element 'hit': body 'cube' carries no contact "
                                     "surface 'side' (it has: top)");
  // A penalty per vertex takes a stiffness; the Hertz materials need a sphere's radius.
  const std::string per_vertex = R"(gravity: [0, 0, 0]
bodies:
  cube: {flexible: {file: cube.sid.h5}}
forces:
  - {name: floor, type: surface_plane_contact, body: cube, surface: top, plane: {body: ground},
     law: hertz, materials: {surface: {youngs_modulus: 2.1e11, poissons_ratio: 0.3}}}
simulation: {end_time: 1e-5, output_interval: 1e-6}
)";
  flexmbs::testing::ExpectInputError(Simulate(per_vertex), "forces[0].materials: unknown key 'materials'");
}

}  // namespace
