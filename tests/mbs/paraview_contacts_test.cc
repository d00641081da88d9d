// The contacts block of the ParaView files (mbs/paraview_writer.h, docs/results.md "ParaView
// files"): every contact point in contact with its load on body A, read back by VTK's own reader
// (tests/paraview_read_back.h). A ball pressed into the floor by a compliant contact (force
// element) and a ball resting on it under a unilateral contact after one Moreau-Jean step (its
// impulse over the step, the weight); a sample without contact has an empty block.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "mbs/contact_force.h"
#include "mbs/moreau_jean.h"
#include "mbs/paraview_writer.h"
#include "mbs/rigid_body.h"
#include "mbs/unilateral_contact.h"
#include "tests/paraview_read_back.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;

constexpr double kMass = 1.0, kRadius = 0.1, kG = 9.81, kStiffness = 1e5;  // [kg], [m], [m/s^2], [N/m]

/// Adds a solid ball of kMass and kRadius named `name` with the marker "centre".
void AddBall(MultibodySystem& system, const std::string& name) {
  system.AddBody(std::make_unique<RigidBody>(
      name, kMass, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.4 * kMass * kRadius * kRadius,
      std::vector<RigidBodyMarker>{{"centre", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
}

Eigen::Vector3d Row(const nlohmann::json& rows, std::size_t k) {
  return {rows[k][0].get<double>(), rows[k][1].get<double>(), rows[k][2].get<double>()};
}

TEST(ParaviewContacts, EveryContactPointIsDrawnWithItsLoad) {
  MultibodySystem system(Eigen::Vector3d(0.0, 0.0, -kG));
  AddBall(system, "resting");
  AddBall(system, "pressed");
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "floor", system.Marker("resting", "centre"), MarkerRef::Ground(Eigen::Vector3d::Zero()), kRadius, UnilateralLaw{}));
  system.AddForceElement(std::make_unique<SpherePlaneContact>("press", system.Marker("pressed", "centre"),
                                                              MarkerRef::Ground(Eigen::Vector3d::Zero()), kRadius,
                                                              kStiffness, 0.0, 1.0));
  Eigen::VectorXd y = system.NeutralState(), x(7);
  x << 0.3, -0.2, kRadius, 1.0, 0.0, 0.0, 0.0;  // resting on the floor
  system.SetBodyState(0, x, Eigen::VectorXd::Zero(6), y);
  x.head<3>() << -0.5, 0.4, kRadius - 1e-3;  // 1 mm into it
  system.SetBodyState(1, x, Eigen::VectorXd::Zero(6), y);

  // A first sample with the pressed ball lifted clear and no step yet: an empty contacts block.
  Eigen::VectorXd lifted = y;
  lifted(system.position_offset(1) + 2) += 0.01;
  MoreauJeanStepper stepper(system, MoreauJeanOptions{1e-3});
  const MoreauJeanStepReport report = stepper.Step(0.0, 1e-3, y);
  const fs::path dir = fs::temp_directory_path() / fmt::format("flexmbs_paraview_contacts_{}", getpid());
  fs::create_directories(dir);
  {
    ParaviewWriter writer(system, dir / "run.pvd");
    ASSERT_TRUE(writer.Record(0.0, lifted));
    ASSERT_TRUE(writer.Record(1e-3, y, report));
  }
  const nlohmann::json samples = flexmbs::testing::ReadParaviewCollection(dir / "run.pvd", dir);
  fs::remove_all(dir);
  ASSERT_EQ(samples.size(), 2u);
  ASSERT_EQ(samples[0]["blocks"].size(), 3u);
  EXPECT_EQ(samples[0]["blocks"][2]["points"].size(), 0u);
  const nlohmann::json& blocks = samples[1]["blocks"];
  ASSERT_EQ(blocks.size(), 3u);
  const nlohmann::json& contacts = blocks[2];
  EXPECT_EQ(contacts["name"], "contacts");
  ASSERT_EQ(contacts["points"].size(), 2u);
  ASSERT_EQ(contacts["cells"].size(), 2u);
  const nlohmann::json& data = contacts["point_data"];

  // The unilateral contact (id 0): the resting ball's lowest point, its impulse over the step m g h
  // as the force m g up (Lemke's one pivot: round-off).
  EXPECT_EQ(data["contact_id"][0], 0);
  EXPECT_LT((Row(contacts["points"], 0) - Eigen::Vector3d(0.3, -0.2, 0.0)).norm(), 1e-12);
  EXPECT_LT((Row(data["force"], 0) - Eigen::Vector3d(0.0, 0.0, kMass * kG)).norm(), 1e-12);
  EXPECT_LT((Row(data["normal"], 0) - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(data["normal_force"][0].get<double>(), kMass * kG, 1e-12);

  // The force element (id 1 = one unilateral contact + its index 0): the pressed ball's lowest
  // point and k delta up, delta from the state after the step (the same formula on the same state:
  // round-off).
  const Eigen::Vector3d p_pressed_W = y.segment<3>(system.position_offset(1));
  const double delta = kRadius - p_pressed_W.z();
  EXPECT_EQ(data["contact_id"][1], 1);
  EXPECT_LT((Row(contacts["points"], 1) - (p_pressed_W - kRadius * Eigen::Vector3d::UnitZ())).norm(), 1e-12);
  EXPECT_NEAR(data["normal_force"][1].get<double>(), kStiffness * delta, 1e-12);
  EXPECT_LT((Row(data["force"], 1) - kStiffness * delta * Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

}  // namespace
}  // namespace flexmbs::mbs
