// mbs/spur_gear_contact with a joint law (contact::MeshLaw::joint): teeth coupled through their
// rims and the flattening at each pair's load in the force element. Its Jacobian carries the
// pairs' cross terms (against central differences of its forces); a single pair gives the forces
// of the pair's own law to the bit; a slowly driven pair settles on the static transmission error
// of the same law; the implicit method needs fewer Newton iterations with the cross terms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/tooth_stiffness.h"
#include "mbs/multibody_system.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "mbs/spur_gear_contact.h"
#include "tests/input_error.h"
#include "tests/mbs/spur_gear_test_pair.h"
#include "tests/support/driven_gear_pair.h"

namespace flexmbs::mbs {
namespace {

using gear_test::AddFreeWheelsInMesh;
using gear_test::DoubleContactState;
using gear_test::GearScene;
using gear_test::JacobianErrors;
using gear_test::kCentre;

/// The mesh law a scene entry of the driven pair gives with `teeth_keys` (a `teeth` entry).
contact::MeshLaw SceneLaw(const std::string& teeth_keys) {
  GearScene files;
  const Scene scene = LoadScene(files.Write(flexmbs::testing::DrivenGearPairScene(
      0.0, std::string(flexmbs::testing::kDrivenPairGearKeys) + teeth_keys)));
  return dynamic_cast<const SpurGearContact&>(scene.system->force_element(1)).law();
}

/// The driven pair's teeth coupled through the rims (FE tables) and the same teeth alone.
const std::string kCoupled = flexmbs::testing::kDrivenPairCoupledTeeth;
/// The one-tooth FE tables with the flattening at each pair's load.
const std::string kAtLoad =
    std::string(flexmbs::testing::kDrivenPairFeTeeth) + "      flattening: at_load\n";

/// `law` without its rims' coupling and with the flattening linearised: each pair its own law.
contact::MeshLaw PairsAlone(const contact::GearPair& pair, const contact::MeshLaw& law) {
  contact::ElasticTeeth teeth = *law.teeth();
  teeth.rim1.reset();
  teeth.rim2.reset();
  teeth.flattening_at_load = false;
  return contact::MeshLaw(pair, teeth, 8e3);
}

/// The number of tooth pairs in contact at y.
int PairsInContact(const MultibodySystem& system, const SpurGearContact& mesh,
                   const Eigen::VectorXd& y) {
  int in = 0;
  for (const contact::ToothPair& tp : mesh.ToothPairs(0.0, system, y)) in += tp.gap < 0.0;
  return in;
}

// Two free wheels in double contact 5 um deep: the joint law's Jacobian against central
// differences of its forces, and the Jacobian of each pair's own law (what one compliant contact
// per pair gives, no cross terms) against the same differences. In u both are exact (the damping
// is each pair's); in the turns the cross terms are what the pairs' own Jacobian misses; left
// out in both: the tables' change along the path (dq/dt delta).
TEST(SpurGearJoint, JacobianCarriesTheCrossTermsOfThePairsInMesh) {
  for (const std::string& keys : {kCoupled, kAtLoad}) {
    const contact::MeshLaw law = SceneLaw(keys);
    MultibodySystem system(Eigen::Vector3d::Zero());
    const contact::GearPair pair =
        AddFreeWheelsInMesh(system, [&](const contact::GearPair&) { return law; });
    const auto& mesh = dynamic_cast<const SpurGearContact&>(system.force_element(0));
    const SpurGearContact alone("alone", system.Marker("pinion", "axis"),
                                system.Marker("wheel", "axis"), pair, PairsAlone(pair, law));
    const Eigen::VectorXd y = DoubleContactState(system, pair);
    ASSERT_EQ(PairsInContact(system, mesh, y), 2);
    const auto [joint_u, joint_x] = JacobianErrors(system, mesh, y);
    const auto [alone_u, alone_x] = JacobianErrors(system, mesh, alone, y);
    std::printf("[measured] %s: the element's Jacobian against differences: u %.2g, turns %.2g; "
                "each pair's own law's: u %.2g, turns %.2g\n",
                law.coupled() ? "rims coupled" : "flattening at load", joint_u, joint_x, alone_u,
                alone_x);
    // Measured u 2.3e-11 (coupled), 2.0e-11 (at load); turns 3.1e-4, 3.4e-4 (the tables' change
    // along the path, left out); each pair's own law's turns 7.3e-2 (no cross terms, 230 times
    // the element's), 1.7e-2 (the stiffness at w_ref instead of the load's, 50 times).
    EXPECT_LT(joint_u, 2.5e-10);
    EXPECT_LT(joint_x, 3.5e-3);
    EXPECT_GT(alone_x, 10.0 * joint_x);
  }
}

// In single contact the rims couple nothing: the coupled element's forces are those of the same
// teeth without the rims to the bit (and the linearised law's are what one CompliantContact per
// pair gave before the joint law existed: the element's code path for them is unchanged).
TEST(SpurGearJoint, SinglePairGivesItsOwnLawsForcesToTheBit) {
  const contact::MeshLaw law = SceneLaw(kCoupled);
  MultibodySystem system(Eigen::Vector3d::Zero());
  const contact::GearPair pair =
      AddFreeWheelsInMesh(system, [&](const contact::GearPair&) { return law; });
  const auto& mesh = dynamic_cast<const SpurGearContact&>(system.force_element(0));
  const SpurGearContact alone("alone", system.Marker("pinion", "axis"),
                              system.Marker("wheel", "axis"), pair, PairsAlone(pair, law));
  Eigen::VectorXd y;
  for (double phi1 = 0.3; phi1 < 0.7; phi1 += 1e-3) {
    y = DoubleContactState(system, pair, phi1);
    if (PairsInContact(system, mesh, y) == 1) break;
  }
  ASSERT_EQ(PairsInContact(system, mesh, y), 1);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(system.num_velocities()), h_alone = h;
  mesh.AddForces(0.0, system, y, h);
  alone.AddForces(0.0, system, y, h_alone);
  EXPECT_GT(h.norm(), 0.0);
  for (Eigen::Index i = 0; i < h.size(); ++i) EXPECT_EQ(h(i), h_alone(i)) << i;
  EXPECT_EQ(mesh.MeshForce(0.0, system, y), alone.MeshForce(0.0, system, y));
}

// The `teeth` entry's rims (`rim: {roll, ahead, behind}` per wheel, `.nan` off the neighbour's
// flank) and `flattening: at_load` reach the element's law.
TEST(SpurGearJoint, TeethEntryGivesTheRimsAndTheFlatteningAtLoad) {
  const contact::MeshLaw coupled = SceneLaw(kCoupled);
  ASSERT_TRUE(coupled.coupled());
  EXPECT_TRUE(coupled.joint());
  EXPECT_EQ(coupled.teeth()->rim1->ahead[2], 3.2747e-12);
  EXPECT_TRUE(std::isnan(coupled.teeth()->rim1->ahead[3]));
  EXPECT_EQ(coupled.teeth()->rim2->behind[6], 1.7603e-12);
  EXPECT_FALSE(coupled.teeth()->flattening_at_load);
  const contact::MeshLaw at_load = SceneLaw(kAtLoad);
  EXPECT_TRUE(at_load.teeth()->flattening_at_load);
  EXPECT_FALSE(at_load.coupled());
  EXPECT_FALSE(SceneLaw(std::string(flexmbs::testing::kDrivenPairFeTeeth) +
                        "      flattening: linearised\n")
                   .joint());
}

// Bad rims and flattening: one line at the item, naming the element and the value.
TEST(SpurGearJoint, BadRimsAndFlatteningAreOneLineErrors) {
  GearScene files;
  const auto refused = [&](const std::string& teeth) {
    return flexmbs::testing::InputErrorMessage([&] {
      LoadScene(files.Write(flexmbs::testing::DrivenGearPairScene(
          0.0, std::string(flexmbs::testing::kDrivenPairGearKeys) + teeth)));
    });
  };
  const auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  std::string message = refused(replaced(kAtLoad, "at_load", "sometimes"));
  EXPECT_NE(message.find("teeth.flattening: 'sometimes' must be one of: linearised, at_load"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  // gear 2's rim left out
  const std::size_t rim2 = kCoupled.rfind(",\n              rim:");
  message = refused(kCoupled.substr(0, rim2) + "}\n");
  EXPECT_NE(message.find("force element 'mesh': elastic teeth: gear 1's rim coupling without gear "
                         "2's; give both or neither"),
            std::string::npos)
      << message;
  message = refused(replaced(kCoupled, "ahead: [3.6474e-12", "ahead: [3.6474e-11"));
  EXPECT_NE(message.find("force element 'mesh': gear 1 rim: ahead[0] 3.6474e-11 m^2/N must be NaN "
                         "(off the neighbour's flank) or in [0, 1.0694e-11)"),
            std::string::npos)
      << message;
  message = refused(replaced(kCoupled, "rim: {roll: [0.13472", "rim: {roll: [.nan"));
  EXPECT_NE(message.find("teeth.gear1.rim.roll[0]: '.nan' is not a finite number"),
            std::string::npos)
      << message;
  message = refused(replaced(kCoupled, "ahead: [2.6318e-12", "infront: [2.6318e-12"));
  EXPECT_NE(message.find("teeth.gear2.rim.infront: unknown key 'infront'"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs
