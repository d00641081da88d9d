// The unilateral contacts of a scene file and the Moreau-Jean keys (mbs/scene_unilateral.h,
// docs/scene.md "Unilateral contacts"): a scene loads into the system's contacts and the
// stepper's options; every bad key or value is one line naming the file, the item and the value.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <string>

#include "mbs/scene.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;

const char* kBodies = R"(bodies:
  ball:
    rigid: {mass: 1, inertia: [[0.004, 0, 0], [0, 0.004, 0], [0, 0, 0.004]]}
    markers: {centre: {position: [0, 0, 0]}}
    initial: {position: [0, 0, 1.1]}
  other:
    rigid: {mass: 1, inertia: [[0.004, 0, 0], [0, 0.004, 0], [0, 0, 0.004]]}
    markers: {centre: {position: [0, 0, 0]}}
    initial: {position: [0.5, 0, 1.1]}
)";
const char* kContacts = R"(contacts:
  - {name: floor, type: sphere_plane, sphere: {body: ball, marker: centre}, plane: {body: ground}, radius: 0.1, law: unilateral, restitution: 0.9, friction: 0.3}
  - {name: pair, type: sphere_sphere, sphere1: {body: ball, marker: centre}, sphere2: {body: other, marker: centre}, radius1: 0.1, radius2: 0.2}
)";
const char* kMoreauJean = "simulation: {end_time: 1, method: moreau_jean, step: 1e-3, theta: 0.6}\n";

/// `text` with `from` replaced by `to` (once; `from` must occur).
std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class UnilateralSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("flexmbs_unilateral_scene_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& text) const {
    const fs::path file = dir_ / "scene.yaml";
    std::ofstream(file) << text;
    return file;
  }
  /// The InputError of loading `text` with `from` replaced by `to` (once, in the contacts).
  std::string Refused(const std::string& text, const std::string& from, const std::string& to) const {
    const fs::path file = Write(Replaced(text, from, to));
    return flexmbs::testing::InputErrorMessage([&] { LoadScene(file); });
  }
  fs::path dir_;
};

TEST_F(UnilateralSceneTest, ContactsAndMoreauJeanKeysLoad) {
  const Scene scene = LoadScene(Write(std::string(kBodies) + kContacts + kMoreauJean));
  ASSERT_EQ(scene.system->num_unilateral_contacts(), 2);
  const UnilateralContact& floor = scene.system->unilateral_contact(0);
  EXPECT_EQ(floor.name(), "floor");
  EXPECT_EQ(floor.type(), "sphere_plane");
  EXPECT_EQ(floor.law().restitution, 0.9);
  EXPECT_EQ(floor.law().friction, 0.3);
  EXPECT_EQ(scene.system->unilateral_contact(1).type(), "sphere_sphere");
  EXPECT_EQ(scene.system->unilateral_contact(1).law().restitution, 0.0);  // defaults: e = 0, mu = 0
  ASSERT_TRUE(scene.options.moreau_jean.has_value());
  EXPECT_EQ(scene.options.moreau_jean->step, 1e-3);
  EXPECT_EQ(scene.options.moreau_jean->theta, 0.6);
  // The gap of the floor at the initial state: 1.1 - 0.1 m.
  const UnilateralContactKinematics k = floor.Evaluate(0.0, *scene.system, scene.initial_state).front();
  EXPECT_NEAR(k.g_N, 1.0, 1e-15);
  // Without moreau_jean the keys of the ODE methods stay as they were.
  const Scene explicit_scene = LoadScene(Write(std::string(kBodies) + "simulation: {end_time: 1}\n"));
  EXPECT_FALSE(explicit_scene.options.moreau_jean.has_value());
}

TEST_F(UnilateralSceneTest, BadContactsAreNamedWithTheirItemAndValue) {
  const std::string text = std::string(kBodies) + kContacts + kMoreauJean;
  std::string message = Refused(text, "sphere: {body: ball", "sphere: {body: bal");
  EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("contacts[0].sphere"), std::string::npos) << message;
  EXPECT_NE(message.find("'bal'"), std::string::npos) << message;
  message = Refused(text, "sphere2: {body: other, marker: centre}", "sphere2: {body: other, marker: rim}");
  EXPECT_NE(message.find("contacts[1].sphere2"), std::string::npos) << message;
  EXPECT_NE(message.find("rim"), std::string::npos) << message;
  message = Refused(text, "radius: 0.1", "radius: -0.1");
  EXPECT_NE(message.find("contacts[0].radius: contact 'floor': -0.1 m must be > 0"), std::string::npos) << message;
  message = Refused(text, "radius2: 0.2", "radius2: 0");
  EXPECT_NE(message.find("contacts[1].radius2: contact 'pair': 0 m must be > 0"), std::string::npos) << message;
  message = Refused(text, "restitution: 0.9", "restitution: 1.5");
  EXPECT_NE(message.find("contacts[0].restitution: contact 'floor': 1.5 must be in [0, 1]"), std::string::npos)
      << message;
  message = Refused(text, "friction: 0.3", "friction: -0.2");
  EXPECT_NE(message.find("contacts[0].friction: contact 'floor': -0.2 must be >= 0"), std::string::npos) << message;
  message = Refused(text, "law: unilateral", "law: hertz");
  EXPECT_NE(message.find("contacts[0].law: contact 'floor': law 'hertz' must be unilateral"), std::string::npos)
      << message;
  message = Refused(text, "type: sphere_sphere", "type: cone_plane");
  EXPECT_NE(message.find("contacts[1].type: contact 'pair': 'cone_plane' must be one of: sphere_plane, "
                         "sphere_sphere, box_plane, cylinder_plane"),
            std::string::npos)
      << message;
  message = Refused(text, "name: pair", "name: floor");
  EXPECT_NE(message.find("contact 'floor' defined twice"), std::string::npos) << message;
  message = Refused(text, "sphere2: {body: other", "sphere2: {body: ball");
  EXPECT_NE(message.find("contact 'pair': both shapes are on one body"), std::string::npos) << message;
}

TEST_F(UnilateralSceneTest, UnilateralContactsNeedMoreauJeanAndMoreauJeanNeedsItsStep) {
  const std::string contacts = std::string(kBodies) + kContacts;
  std::string message = Refused(contacts + kMoreauJean, "method: moreau_jean, step: 1e-3, theta: 0.6", "method: implicit");
  EXPECT_NE(message.find("contacts[0]: contact 'floor' is unilateral, which only simulation.method moreau_jean "
                         "or event_driven integrates (compliant contact under explicit or implicit: the force elements "
                         "sphere_plane_contact"),
            std::string::npos)
      << message;
  message = Refused(contacts + "simulation: {end_time: 1}\n", "end_time: 1", "end_time: 1");
  EXPECT_NE(message.find("contact 'floor' is unilateral"), std::string::npos) << message;
  message = Refused(contacts + kMoreauJean, ", step: 1e-3", "");
  EXPECT_NE(message.find("simulation.method: moreau_jean needs step: the fixed time step [s]"), std::string::npos)
      << message;
  message = Refused(contacts + kMoreauJean, "step: 1e-3", "step: -1e-3");
  EXPECT_NE(message.find("simulation.step: -0.001 s must be > 0"), std::string::npos) << message;
  message = Refused(contacts + kMoreauJean, "theta: 0.6", "theta: 0.4");
  EXPECT_NE(message.find("simulation.theta: 0.4 must be in [0.5, 1]"), std::string::npos) << message;
  message = Refused(std::string(kBodies) + "simulation: {end_time: 1, step: 1e-3}\n", "step", "step");
  EXPECT_NE(message.find("simulation.step: only for method moreau_jean"), std::string::npos) << message;
  message = Refused(contacts + kMoreauJean, "method: moreau_jean", "method: event_driven");
  EXPECT_NE(message.find("simulation.step: only for method moreau_jean"), std::string::npos) << message;
}

// The ODE integrator's keys were read and ignored under Moreau-Jean (issue 22): each is refused
// at its item, as event_driven refuses the keys it does not use.
TEST_F(UnilateralSceneTest, OdeIntegratorKeysWithMoreauJeanAreRefused) {
  const std::string scene = std::string(kBodies) + kContacts + kMoreauJean;
  for (const std::string key : {"relative_tolerance: 1e-6", "absolute_tolerance: 1e-9", "max_step: 1e-3",
                                "fixed_step: 1e-4", "baumgarte_frequency: 100", "jacobian: model", "newton: dense"}) {
    const std::string message = Refused(scene, "theta: 0.6", "theta: 0.6, " + key);
    EXPECT_NE(message.find("simulation." + key.substr(0, key.find(':')) + ": not for method moreau_jean"),
              std::string::npos)
        << message;
  }
}

TEST_F(UnilateralSceneTest, BoxPlaneLoadsItsHalfExtentsAndRefusesAnEdgeOfZero) {
  const std::string box = std::string(kBodies) +
                          "contacts:\n  - {name: seat, type: box_plane, box: {body: other, marker: centre}, "
                          "size: [0.2, 0.1, 0.04], plane: {body: ground}, friction: 0.4}\n" +
                          kMoreauJean;
  const Scene scene = LoadScene(Write(box));
  ASSERT_EQ(scene.system->num_unilateral_contacts(), 1);
  const UnilateralContact& seat = scene.system->unilateral_contact(0);
  EXPECT_EQ(seat.type(), "box_plane");
  EXPECT_EQ(seat.num_points(), 8);
  // The lowest corners of the box (centre 1.1 m up, 0.04 m high) 1.08 m above the ground.
  double lowest = 1e9;
  for (const UnilateralContactKinematics& k : seat.Evaluate(0.0, *scene.system, scene.initial_state)) {
    lowest = std::min(lowest, k.g_N);
  }
  EXPECT_NEAR(lowest, 1.08, 1e-15);
  const std::string message = Refused(box, "size: [0.2, 0.1, 0.04]", "size: [0.2, 0, 0.04]");
  EXPECT_NE(message.find("contacts[0].size: contact 'seat': the box's edges [m] must be > 0, not (0.2, 0, 0.04)"),
            std::string::npos)
      << message;
  // Its penalty counterpart in forces: (box_plane_contact).
  const std::string penalty = std::string(kBodies) +
                              "forces:\n  - {name: seat, type: box_plane_contact, box: {body: other, marker: centre}, "
                              "size: [0.2, 0.1, 0.04], plane: {body: ground}, stiffness: 1e5, damping: 10}\n" +
                              "simulation: {end_time: 1}\n";
  const Scene compliant = LoadScene(Write(penalty));
  ASSERT_EQ(compliant.system->num_force_elements(), 1);
  EXPECT_TRUE(compliant.system->force_element(0).is_contact());
  const std::string refused = Refused(penalty, "size: [0.2, 0.1, 0.04]", "size: [-0.2, 0.1, 0.04]");
  EXPECT_NE(refused.find("forces[0].size: force element 'seat': the box's edges [m] must be > 0, not (-0.2, 0.1, "
                         "0.04)"),
            std::string::npos)
      << refused;
}

TEST_F(UnilateralSceneTest, ImpactLevelPositionLoadsAndNeedsThetaOneAndNoRestitution) {
  const std::string position = "simulation: {end_time: 1, method: moreau_jean, step: 1e-3, theta: 1, impact_level: position}\n";
  const std::string plastic = std::string(kBodies) + kContacts;
  const Scene scene = LoadScene(Write(Replaced(plastic, "restitution: 0.9", "restitution: 0") + position));
  ASSERT_TRUE(scene.options.moreau_jean.has_value());
  EXPECT_EQ(scene.options.moreau_jean->impact_level, ImpactLevel::kPosition);
  EXPECT_EQ(LoadScene(Write(plastic + kMoreauJean)).options.moreau_jean->impact_level, ImpactLevel::kVelocity);
  std::string message = Refused(plastic + position, "restitution: 0.9", "restitution: 0.9");
  EXPECT_NE(message.find("contacts[0].restitution: 0.9: impact_level position takes no restitution"), std::string::npos)
      << message;
  message = Refused(plastic + position, "theta: 1", "theta: 0.5");
  EXPECT_NE(message.find("simulation.impact_level: position needs theta: 1 (the gap the positions reach), not 0.5"),
            std::string::npos)
      << message;
  message = Refused(plastic + position, "impact_level: position", "impact_level: acceleration");
  EXPECT_NE(message.find("simulation.impact_level: 'acceleration' must be one of: velocity, position"),
            std::string::npos)
      << message;
  message = Refused(plastic + position, "method: moreau_jean, step: 1e-3, theta: 1, ", "method: event_driven, ");
  EXPECT_NE(message.find("simulation.impact_level: only for method moreau_jean"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs
