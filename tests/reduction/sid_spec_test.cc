// The `sid:` section of a body file: what it accepts and the one-line errors.
#include "reduction/sid_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kNodeSets = {"mid", "tip", "pad", "rim"};
const std::vector<std::string> kInterfaceMarkers = {"hub"};

fs::path WriteBody(const std::string& sid_yaml) {
  // One folder per test and process: CTest runs the tests of this file concurrently.
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir =
      fs::temp_directory_path() /
      (std::string("flexmbs_sid_spec_") + test->name() + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "body.yaml";
  std::ofstream(path) << "name: b\n" << sid_yaml;
  return path;
}

SidSpec Load(const std::string& sid_yaml) {
  return LoadSidSpec(WriteBody(sid_yaml), kNodeSets, kInterfaceMarkers);
}

std::string ErrorOf(const std::string& sid_yaml) {
  return testing::InputErrorMessage([&] { Load(sid_yaml); });
}

TEST(SidSpec, ReadsAFullSection) {
  const SidSpec spec = Load(R"(sid:
  markers:
    - {name: mid, node_set: mid, coupling: averaging}
    - {name: tip, node_set: tip, coupling: rigid, position: [1, 0, 0.5]}
    - {name: tip_node, node_set: tip, coupling: node}
  contact_surfaces: [pad, rim]
  damping: {modal_ratios: [0.01, 0.02, 0]}
  geometric_stiffening: false
)");
  ASSERT_EQ(spec.markers.size(), 3u);
  EXPECT_EQ(spec.markers[0].name, "mid");
  EXPECT_EQ(spec.markers[0].node_set, "mid");
  EXPECT_EQ(spec.markers[0].coupling, MarkerCoupling::kAveraging);
  EXPECT_FALSE(spec.markers[0].p_BoMarker_B.has_value());
  EXPECT_EQ(spec.markers[1].coupling, MarkerCoupling::kRigid);
  EXPECT_EQ(*spec.markers[1].p_BoMarker_B, Eigen::Vector3d(1, 0, 0.5));
  EXPECT_EQ(spec.markers[2].coupling, MarkerCoupling::kNode);
  EXPECT_EQ(spec.contact_surfaces, (std::vector<std::string>{"pad", "rim"}));
  EXPECT_EQ(spec.damping.kind, DampingKind::kModal);
  EXPECT_EQ(spec.damping.modal_ratios, (std::vector<double>{0.01, 0.02, 0.0}));
  EXPECT_FALSE(spec.geometric_stiffening);
}

TEST(SidSpec, ReadsEachDampingForm) {
  const DampingSpec one = Load("sid: {damping: {modal_ratio: 0.02}}\n").damping;
  EXPECT_EQ(one.kind, DampingKind::kModal);
  EXPECT_EQ(one.modal_ratio, 0.02);
  EXPECT_TRUE(one.modal_ratios.empty());
  const DampingSpec rayleigh =
      Load("sid: {damping: {rayleigh: {mass: 0.5, stiffness: 1e-5}}}\n").damping;
  EXPECT_EQ(rayleigh.kind, DampingKind::kRayleigh);
  EXPECT_EQ(rayleigh.rayleigh_mass_per_s, 0.5);
  EXPECT_EQ(rayleigh.rayleigh_stiffness_s, 1e-5);
  const DampingSpec stiffness_only =
      Load("sid: {damping: {rayleigh: {stiffness: 2e-5}}}\n").damping;
  EXPECT_EQ(stiffness_only.rayleigh_mass_per_s, 0.0);
  EXPECT_EQ(stiffness_only.rayleigh_stiffness_s, 2e-5);
}

TEST(SidSpec, DefaultsWithoutTheSection) {
  const SidSpec spec = Load("reduction: {modes: 3}\n");
  EXPECT_TRUE(spec.markers.empty());
  EXPECT_TRUE(spec.contact_surfaces.empty());
  EXPECT_EQ(spec.damping.kind, DampingKind::kNone);
  EXPECT_TRUE(spec.geometric_stiffening);
}

TEST(SidSpec, BadInputGivesOneLineErrorsNamingFileItemAndValue) {
  const std::string file = WriteBody("").string();
  EXPECT_EQ(ErrorOf("sid: {stiffening: true}\n"),
            file +
                ":2:7: sid.stiffening: unknown key 'stiffening' (expected one of: markers, "
                "contact_surfaces, damping, "
                "geometric_stiffening)");
  EXPECT_EQ(ErrorOf("sid:\n  markers:\n    - {name: a, node_set: root, coupling: rigid}\n"),
            file +
                ":4:27: sid.markers[0].node_set: 'root' is not one of the body's node_sets (mid, "
                "tip, pad, rim)");
  EXPECT_EQ(
      ErrorOf("sid:\n  markers:\n    - {name: a, node_set: tip, coupling: glued}\n"),
      file + ":4:42: sid.markers[0].coupling: 'glued' must be one of: node, rigid, averaging");
  EXPECT_EQ(ErrorOf("sid:\n  markers:\n    - {name: a, node_set: tip}\n"),
            file + ":4:7: sid.markers[0]: missing key 'coupling'");
  EXPECT_EQ(
      ErrorOf("sid:\n  markers:\n    - {name: a, node_set: tip, coupling: node, weight: 2}\n"),
      file +
          ":4:48: sid.markers[0].weight: unknown key 'weight' (expected one of: name, node_set, "
          "coupling, position)");
  EXPECT_EQ(ErrorOf("sid:\n  markers:\n    - {name: '', node_set: tip, coupling: node}\n"),
            file + ":4:14: sid.markers[0].name: a marker name must not be empty");
  EXPECT_EQ(ErrorOf("sid:\n  markers:\n    - {name: a, node_set: tip, coupling: node}\n"
                    "    - {name: a, node_set: mid, coupling: rigid}\n"),
            file + ":5:14: sid.markers[1].name: marker name 'a' is used twice");
  EXPECT_EQ(
      ErrorOf("sid:\n  markers:\n    - {name: hub, node_set: tip, coupling: rigid}\n"),
      file +
          ":4:14: sid.markers[0].name: 'hub' is the name of an interface marker of the reduction");
  EXPECT_EQ(
      ErrorOf("sid:\n  markers:\n    - {name: a, node_set: tip, coupling: node, position: [0, 0, "
              "1]}\n"),
      file +
          ":4:58: sid.markers[0].position: a 'node' marker sits at its FE node: a position is for "
          "rigid or averaging markers");
  EXPECT_EQ(
      ErrorOf(
          "sid:\n  markers:\n    - {name: a, node_set: tip, coupling: rigid, position: [0, 1]}\n"),
      file + ":4:59: sid.markers[0].position: expected 3 coordinates, got 2");
  EXPECT_EQ(ErrorOf("sid:\n  contact_surfaces: [pad, hub]\n"),
            file +
                ":3:27: sid.contact_surfaces[1]: 'hub' is not one of the body's node_sets (mid, "
                "tip, pad, rim)");
  EXPECT_EQ(ErrorOf("sid:\n  contact_surfaces: [pad, rim, pad]\n"),
            file + ":3:32: sid.contact_surfaces[2]: contact surface 'pad' is listed twice");
  EXPECT_EQ(ErrorOf("sid:\n  damping: {modal_ratio: -0.02}\n"),
            file + ":3:26: sid.damping.modal_ratio: damping ratio -0.02 must be >= 0");
  EXPECT_EQ(ErrorOf("sid:\n  damping: {modal_ratio: .nan}\n"),
            file + ":3:26: sid.damping.modal_ratio: '.nan' is not a finite number");
  EXPECT_EQ(ErrorOf("sid:\n  damping: {modal_ratios: [0.01, -1]}\n"),
            file + ":3:34: sid.damping.modal_ratios[1]: damping ratio -1 must be >= 0");
  EXPECT_EQ(ErrorOf("sid:\n  damping: {modal_ratios: []}\n"),
            file +
                ":3:27: sid.damping.modal_ratios: give one damping ratio per elastic mode (or "
                "'modal_ratio' for all)");
  EXPECT_EQ(
      ErrorOf("sid:\n  damping: {modal_ratio: 0.02, rayleigh: {mass: 1}}\n"),
      file + ":3:12: sid.damping: give exactly one of 'modal_ratio', 'modal_ratios' or 'rayleigh'");
  EXPECT_EQ(
      ErrorOf("sid:\n  damping: {}\n"),
      file + ":3:12: sid.damping: give exactly one of 'modal_ratio', 'modal_ratios' or 'rayleigh'");
  EXPECT_EQ(ErrorOf("sid:\n  damping: {rayleigh: {}}\n"),
            file +
                ":3:23: sid.damping.rayleigh: give 'mass' (a [1/s]) and/or 'stiffness' (b [s]) of "
                "De = a Me + b Ke");
  EXPECT_EQ(
      ErrorOf("sid:\n  damping: {rayleigh: {mass: 1, stiffness: -1e-5}}\n"),
      file + ":3:44: sid.damping.rayleigh.stiffness: stiffness coefficient -1e-05 must be >= 0");
  EXPECT_EQ(ErrorOf("sid:\n  geometric_stiffening: maybe\n"),
            file + ":3:25: sid.geometric_stiffening: 'maybe' is not true or false");
}

TEST(SidSpec, MeshChecksNameTheMarkerInTheFile) {
  const fs::path body = WriteBody(
      "sid:\n  markers:\n    - {name: a, node_set: tip, coupling: averaging}\n"
      "    - {name: b, node_set: mid, coupling: node}\n");
  const SidSpec spec = LoadSidSpec(body, kNodeSets, kInterfaceMarkers);
  const std::map<std::string, std::vector<int>> mesh_sets = {{"tip", {4, 5, 9}}, {"mid", {2, 3}}};
  EXPECT_EQ(testing::InputErrorMessage([&] { CheckMarkerNodeSets(spec.markers, mesh_sets); }),
            body.string() +
                ":5:7: sid.markers[1]: coupling 'node' needs a node set of exactly one FE node; "
                "'mid' has 2");
  EXPECT_EQ(testing::InputErrorMessage([&] {
              CheckMarkerNodeSets(spec.markers, {{"tip", {4, 5, 9}}});
            }),
            body.string() + ":5:7: sid.markers[1]: the mesh has no node set 'mid'");
  EXPECT_EQ(testing::InputErrorMessage([&] {
              CheckMarkerNodeSets(spec.markers, {{"tip", {4, 5, 9}}, {"mid", {3}}});
            }),
            "no error");
}

TEST(SidSpec, ModalRatioCountIsCheckedAgainstTheElasticModes) {
  const fs::path body = WriteBody("sid:\n  damping:\n    modal_ratios: [0.01, 0.02]\n");
  const DampingSpec damping = LoadSidSpec(body, kNodeSets, kInterfaceMarkers).damping;
  EXPECT_EQ(testing::InputErrorMessage([&] { CheckModalRatioCount(damping, 3); }),
            body.string() +
                ":4:19: sid.damping.modal_ratios: 2 damping ratios for 3 elastic modes of the "
                "reduced system");
  EXPECT_EQ(testing::InputErrorMessage([&] { CheckModalRatioCount(damping, 2); }), "no error");
  // One ratio for every mode fits any count.
  const DampingSpec one = Load("sid: {damping: {modal_ratio: 0.02}}\n").damping;
  EXPECT_EQ(testing::InputErrorMessage([&] { CheckModalRatioCount(one, 7); }), "no error");
}

}  // namespace
}  // namespace flexmbs::reduction
