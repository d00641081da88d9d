// A scene's `teeth: fe` (docs/scene.md, spur_gear_contact): mbs::LoadScene with the hooks of
// `flexmbs simulate` (app/fe_tooth_table.h) computes each wheel's tooth table by gear_tooth_fe,
// equal to the table gear_tooth_fe gives directly for the same wheel, material and options (with
// `rim: true` the three-tooth segment's table and rim coupling); the scene's FE options and
// material reach the FE tooth; bad entries are one-line errors at their item, before any FE run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "app/fe_tooth_table.h"
#include "contact/gears/spur_gear.h"
#include "gear_tooth_fe/tooth_model.h"
#include "mbs/scene.h"
#include "mbs/spur_gear_contact.h"
#include "tests/input_error.h"
#include "tests/support/driven_gear_pair.h"

namespace flexmbs::app {
namespace {

/// A scene file of the driven pair (tests/support/driven_gear_pair.h) with the mesh keys
/// kDrivenPairGearKeys + `teeth`, in a temporary directory removed with the object.
class TeethScene {
 public:
  TeethScene()
      : dir_(std::filesystem::temp_directory_path() /
             ("flexmbs_gear_teeth_scene_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~TeethScene() { std::filesystem::remove_all(dir_); }
  TeethScene(const TeethScene&) = delete;
  TeethScene& operator=(const TeethScene&) = delete;

  std::filesystem::path Write(const std::string& teeth) const {
    const std::filesystem::path file = dir_ / "scene.yaml";
    std::ofstream(file) << flexmbs::testing::DrivenGearPairScene(
        0.0, std::string(flexmbs::testing::kDrivenPairGearKeys) + teeth);
    return file;
  }

 private:
  std::filesystem::path dir_;
};

/// The pair's wheels as kDrivenPairGearKeys gives them.
contact::SpurGearSpec Wheel(int teeth, double shift) {
  return {2e-3, teeth, 20.0 * std::numbers::pi / 180.0, shift, 1.0, 1.25, 0.02};
}

/// The elastic teeth of the scene's element "mesh" (force element 1).
const contact::ElasticTeeth& SceneTeeth(const mbs::Scene& scene) {
  const auto& mesh = dynamic_cast<const mbs::SpurGearContact&>(scene.system->force_element(1));
  const contact::ElasticTeeth* teeth = mesh.law().teeth();
  EXPECT_NE(teeth, nullptr);
  return *teeth;
}

/// The largest |a_k / b_k - 1| over columns `a` and `b` (NaN where the other has NaN); infinite
/// where their lengths or NaNs differ.
double ColumnsApart(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double apart = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::isnan(a[k]) != std::isnan(b[k])) return std::numeric_limits<double>::infinity();
    if (!std::isnan(a[k])) apart = std::max(apart, std::abs(a[k] / b[k] - 1.0));
  }
  return apart;
}

/// Two runs of the same FE tooth repeat to the bit in most runs, not all: on 2 cores under load
/// the compliances came out up to 6.7e-16 (one tooth, 1 of 40 runs) and 1.3e-15 (three-tooth
/// segment, 1 of 20, the same 5443 and 6452 nodes) apart; with OMP_NUM_THREADS=1 none of 50 runs
/// of the one-tooth test differed (6 of 50 without), so an OpenMP region on the path (gmsh's, the
/// one library there using it) likely orders the mesh or its sums differently.
constexpr double kFeRepeats = 1e-14;

/// Expects the scene's table and the FE's: rolls and depths to the bit, compliances within
/// `tolerance` relative (0: to the bit).
void ExpectSameTable(const contact::ToothCompliance& scene, const contact::ToothCompliance& fe,
                     double tolerance = 0.0) {
  EXPECT_EQ(scene.roll, fe.roll);
  EXPECT_LE(ColumnsApart(scene.compliance, fe.compliance), tolerance);
  EXPECT_EQ(scene.centre_depth, fe.centre_depth);
}

// The scene's tables are gear_tooth_fe's for each wheel (z 19, x 0.3 and z 31, x -0.1) with the
// scene's edge (0.8 mm = 0.4 m), load points and material: the same FE model, meshed and solved
// the same way (equal as far as the FE tooth repeats, kFeRepeats).
TEST(GearTeethScene, FeTeethAreTheTablesGearToothFeGivesForEachWheel) {
  TeethScene files;
  const mbs::Scene scene = mbs::LoadScene(
      files.Write("    teeth: {fe: {mesh_size: 8e-4, element_order: 2, loads: 5}, "
                  "youngs_modulus: 2.0e11, poisson_ratio: 0.29}\n"),
      SimulateSceneHooks());
  const contact::ElasticTeeth& teeth = SceneTeeth(scene);
  EXPECT_EQ(teeth.material.youngs_modulus, 2.0e11);
  EXPECT_EQ(teeth.material.poisson_ratio, 0.29);
  gear_tooth_fe::ToothModelOptions options;
  options.geometry.mesh_size = 0.4;
  options.loads = 5;
  const contact::ToothMaterial material{2.0e11, 0.29};
  ExpectSameTable(teeth.tooth1,
                  gear_tooth_fe::ToothComplianceFromFe(
                      contact::MakeSpurGear(Wheel(19, 0.3), "gear 1"), material, options)
                      .compliance,
                  kFeRepeats);
  ExpectSameTable(teeth.tooth2,
                  gear_tooth_fe::ToothComplianceFromFe(
                      contact::MakeSpurGear(Wheel(31, -0.1), "gear 2"), material, options)
                      .compliance,
                  kFeRepeats);
  EXPECT_EQ(teeth.tooth1.roll.size(), 5u);
}

/// Expects the scene's rim coupling and the FE's at the same rolls, their deflections within
/// `tolerance` relative (0: to the bit).
void ExpectSameRim(const std::optional<contact::RimCoupling>& scene, const contact::RimCoupling& fe,
                   double tolerance = 0.0) {
  ASSERT_TRUE(scene.has_value());
  EXPECT_EQ(scene->roll, fe.roll);
  EXPECT_LE(ColumnsApart(scene->ahead, fe.ahead), tolerance);
  EXPECT_LE(ColumnsApart(scene->behind, fe.behind), tolerance);
}

// `fe: {..., rim: true}`: each wheel's tooth on its three-tooth segment, the scene's tables and
// rims' coupling gear_tooth_fe::ToothCouplingFromFe's for the wheel and options (the rolls and
// depths to the bit, the compliances as the FE segment repeats, kFeRepeats); the element's law
// then couples the pairs (its teeth carry both rims).
TEST(GearTeethScene, FeRimTeethAreTheSegmentsTablesAndCouplingGearToothFeGives) {
  TeethScene files;
  const mbs::Scene scene = mbs::LoadScene(
      files.Write("    teeth: {fe: {mesh_size: 8e-4, loads: 7, rim: true}, poisson_ratio: 0.29}\n"),
      SimulateSceneHooks());
  const contact::ElasticTeeth& teeth = SceneTeeth(scene);
  gear_tooth_fe::ToothModelOptions options;
  options.geometry.mesh_size = 0.4;
  options.loads = 7;
  const contact::ToothMaterial material{contact::ToothMaterial{}.youngs_modulus, 0.29};
  const gear_tooth_fe::ToothCoupling fe1 = gear_tooth_fe::ToothCouplingFromFe(
      contact::MakeSpurGear(Wheel(19, 0.3), "gear 1"), material, options);
  const gear_tooth_fe::ToothCoupling fe2 = gear_tooth_fe::ToothCouplingFromFe(
      contact::MakeSpurGear(Wheel(31, -0.1), "gear 2"), material, options);
  ExpectSameTable(teeth.tooth1, fe1.compliance, kFeRepeats);
  ExpectSameTable(teeth.tooth2, fe2.compliance, kFeRepeats);
  ExpectSameRim(teeth.rim1, fe1.rim, kFeRepeats);
  ExpectSameRim(teeth.rim2, fe2.rim, kFeRepeats);
  // Not the one-tooth tables: the three-tooth segment's tooth is softer (the wider rim).
  EXPECT_GT(teeth.tooth1.compliance[3],
            gear_tooth_fe::ToothComplianceFromFe(contact::MakeSpurGear(Wheel(19, 0.3), "gear 1"),
                                                 material, options)
                .compliance.compliance[3]);
}

// `rim: true` asks the FE stage for both wheels' rims (the other options as given) and hands the
// tables it returns to the element; `rim: false` is the one-tooth tables, as without the key.
TEST(GearTeethScene, FeRimAsksForTheRimsAndHandsThemToTheElement) {
  TeethScene files;
  std::vector<mbs::ToothTableRequest> requests;
  const contact::ToothCompliance table{{0.2, 0.5}, {1e-11, 3e-11}, {2e-3, 1e-3}};
  const contact::RimCoupling rim{{0.2, 0.3, 0.5}, {3e-12, 2e-12, std::nan("")}, {1e-12, 2e-12, 3e-12}};
  mbs::SceneHooks hooks{[&](const mbs::ToothTableRequest& request) {
    requests.push_back(request);
    return mbs::ToothTables{table, request.rim ? std::optional(rim) : std::nullopt};
  }};
  const mbs::Scene coupled =
      mbs::LoadScene(files.Write("    teeth: {fe: {loads: 4, rim: true}}\n"), hooks);
  ASSERT_EQ(requests.size(), 2u);
  for (const mbs::ToothTableRequest& r : requests) {
    EXPECT_TRUE(r.rim);
    EXPECT_EQ(r.loads, 4);
  }
  ExpectSameRim(SceneTeeth(coupled).rim1, rim);
  ExpectSameRim(SceneTeeth(coupled).rim2, rim);
  ExpectSameTable(SceneTeeth(coupled).tooth1, table);
  const mbs::Scene alone =
      mbs::LoadScene(files.Write("    teeth: {fe: {rim: false}}\n"), hooks);
  ASSERT_EQ(requests.size(), 4u);
  EXPECT_FALSE(requests[2].rim || requests[3].rim);
  EXPECT_FALSE(SceneTeeth(alone).rim1 || SceneTeeth(alone).rim2);
}

// `teeth: fe` (the word) asks for both wheels, unthinned, with steel and the FE tooth's own
// defaults; the tables it returns are the element's.
TEST(GearTeethScene, TheWordFeAsksForBothWheelsWithTheDefaults) {
  TeethScene files;
  std::vector<mbs::ToothTableRequest> requests;
  const contact::ToothCompliance table{{0.2, 0.5}, {1e-11, 3e-11}, {2e-3, 1e-3}};
  mbs::SceneHooks hooks{[&](const mbs::ToothTableRequest& request) {
    requests.push_back(request);
    return mbs::ToothTables{table, std::nullopt};
  }};
  const mbs::Scene scene = mbs::LoadScene(files.Write("    teeth: fe\n"), hooks);
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0].gear.spec.teeth, 19);
  EXPECT_EQ(requests[1].gear.spec.teeth, 31);
  EXPECT_EQ(requests[1].gear.spec.profile_shift, -0.1);
  // Unthinned: the wheel as MakeSpurGear makes it (the pair has 1e-4 m of backlash).
  EXPECT_EQ(requests[0].gear.base_half_angle,
            contact::MakeSpurGear(Wheel(19, 0.3), "gear 1").base_half_angle);
  for (const mbs::ToothTableRequest& r : requests) {
    EXPECT_FALSE(r.mesh_size || r.element_order || r.loads || r.rim);
    EXPECT_EQ(r.material.youngs_modulus, contact::ToothMaterial{}.youngs_modulus);
    EXPECT_EQ(r.material.poisson_ratio, contact::ToothMaterial{}.poisson_ratio);
  }
  ExpectSameTable(SceneTeeth(scene).tooth1, table);
  ExpectSameTable(SceneTeeth(scene).tooth2, table);
  EXPECT_FALSE(SceneTeeth(scene).rim1 || SceneTeeth(scene).rim2);  // one-tooth tables
}

TEST(GearTeethScene, BadFeEntriesAreOneLineErrorsAtTheirItemBeforeAnyFeRun) {
  TeethScene files;
  int runs = 0;
  mbs::SceneHooks counting{[&](const mbs::ToothTableRequest&) {
    ++runs;
    return mbs::ToothTables{{{0.2, 0.5}, {1e-11, 3e-11}, {2e-3, 1e-3}}, std::nullopt};
  }};
  const auto refused = [&](const std::string& teeth, const mbs::SceneHooks& hooks) {
    return flexmbs::testing::InputErrorMessage([&] { mbs::LoadScene(files.Write(teeth), hooks); });
  };
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
  };
  expect(refused("    teeth: fe\n", {}),
         "forces[1].teeth: force element 'mesh': teeth fe: the FE tooth is computed by `flexmbs "
         "simulate`");
  expect(refused("    teeth: fem\n", counting), "forces[1].teeth: 'fem' must be one of: fe");
  expect(refused("    teeth: {fe: {mesh_size: -1e-3}}\n", counting),
         "forces[1].teeth.fe.mesh_size: -0.001 must be > 0 [m]");
  expect(refused("    teeth: {fe: {element_order: 3}}\n", counting),
         "forces[1].teeth.fe.element_order: 3 must be 1 or 2");
  expect(refused("    teeth: {fe: {loads: 1}}\n", counting),
         "forces[1].teeth.fe.loads: 1 load points: give 2 to 100");
  expect(refused("    teeth: {fe: {size: 1e-3}}\n", counting), "forces[1].teeth.fe.size");
  expect(refused("    teeth: {fe: {rim: 3}}\n", counting),
         "forces[1].teeth.fe.rim: '3' is not true or false");
  expect(refused("    teeth: {fe: {rim: {roll: [0.2, 0.5]}}}\n", counting),
         "forces[1].teeth.fe.rim: expected true or false");
  expect(refused("    teeth: {fe: {rim: true}, movable: {damping: 2e4}}\n", counting),
         "forces[1].teeth.fe.rim: force element 'mesh': movable teeth take no rims' coupling");
  expect(refused("    teeth: {fe: {}, gear1: {roll: [0.2, 0.5]}}\n", counting),
         "forces[1].teeth.gear1");
  expect(refused("    teeth: {fe: {}, poisson_ratio: 0.5}\n", counting),
         "forces[1].teeth: force element 'mesh': Poisson's ratio 0.5 must be in [0, 0.5)");
  expect(refused("    teeth: {fe: {}, youngs_modulus: -2e11}\n", counting),
         "forces[1].teeth: force element 'mesh': Young's modulus [Pa] -200000000000 must be");
  EXPECT_EQ(runs, 0);
  // The FE tooth's own refusal, located at the entry.
  const mbs::SceneHooks refusing{[](const mbs::ToothTableRequest&) -> mbs::ToothTables {
    throw InputError("FE tooth: mesh size 3 m is too large");
  }};
  expect(refused("    teeth: fe\n", refusing),
         "forces[1].teeth: force element 'mesh': FE tooth: mesh size 3 m is too large");
  // Too few load points for the rims' coupling: the FE segment of gear 1 (z 19) with 3 load
  // points hits the neighbour ahead at one of them (the coupling interpolates between two).
  expect(refused("    teeth: {fe: {mesh_size: 8e-4, loads: 3, rim: true}}\n", SimulateSceneHooks()),
         "forces[1].teeth: force element 'mesh': gear 1's FE segment: 1 of its 3 load points "
         "reach the flank of the neighbour ahead; the rims' coupling needs two or more: give "
         "more loads");
}

}  // namespace
}  // namespace flexmbs::app
