// Body files: every bad input is an InputError whose message is one line naming the file,
// the item and the value.
#include "fem/body_spec.h"
#include "tests/input_error.h"
#include "tests/test_data.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

namespace fs = std::filesystem;

// A valid body file. Line and column numbers in the expected messages below refer to it.
constexpr char kValidBody[] = R"(name: beam
geometry:
  file: beam.geo
  mesh_size: 0.01
  element_order: 1
materials:
  steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}
material: steel
node_sets: [clamp, tip]
)";

// `text` with its only occurrence of `from` replaced by `to`.
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' is not in the body text";
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is not unique";
  return text.replace(at, from.size(), to);
}

void ExpectStartsWith(const std::string& text, const std::string& prefix) {
  EXPECT_TRUE(text.starts_with(prefix))
      << "  actual: " << text << "\nexpected: " << prefix << "...";
}

// Each test gets its own folder holding beam.geo (LoadBodySpec checks only that it exists).
class BodySpecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("flexmbs_body_spec_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    Write("beam.geo", "Box(1) = {0, 0, 0, 1, 0.1, 0.1};\n");
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_ / "body.yaml", fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
  }

  fs::path Write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  std::string body() const { return (dir_ / "body.yaml").string(); }

  // The message of the InputError LoadBodySpec throws for a body file holding `text`.
  std::string ErrorOf(const std::string& text) const {
    return ErrorOfFile(Write("body.yaml", text));
  }

  static std::string ErrorOfFile(const fs::path& file) {
    return testing::InputErrorMessage([&] { LoadBodySpec(file); });
  }

  fs::path dir_;
};

TEST_F(BodySpecTest, ValidFileGivesEveryField) {
  const BodySpec spec = LoadBodySpec(Write("body.yaml", kValidBody));
  EXPECT_EQ(spec.name, "beam");
  EXPECT_EQ(spec.geometry_file, (dir_ / "beam.geo").lexically_normal());
  EXPECT_EQ(spec.meshing.mesh_size_m, 0.01);
  EXPECT_EQ(spec.meshing.element_order, 1);
  ASSERT_EQ(spec.materials.count("steel"), 1u);
  EXPECT_EQ(spec.materials.at("steel").youngs_modulus_pa, 2.1e11);
  EXPECT_EQ(spec.materials.at("steel").poisson_ratio, 0.3);
  EXPECT_EQ(spec.materials.at("steel").density_kg_m3, 7850.0);
  EXPECT_EQ(spec.default_material, "steel");
  EXPECT_EQ(spec.node_sets, (std::vector<std::string>{"clamp", "tip"}));
  EXPECT_EQ(spec.mass_matrix, MassMatrixKind::kConsistent);
}

// --- the body file itself ---

TEST_F(BodySpecTest, MissingFileIsNamed) {
  const std::string file = (dir_ / "absent.yaml").string();
  EXPECT_EQ(ErrorOfFile(file), file + ": cannot open the file: No such file or directory");
}

TEST_F(BodySpecTest, DirectoryIsNotABodyFile) {
  EXPECT_EQ(ErrorOfFile(dir_), dir_.string() + ": is a directory, not a YAML file");
}

TEST_F(BodySpecTest, UnreadableFileIsNamed) {
  const fs::path file = Write("body.yaml", kValidBody);
  fs::permissions(file, fs::perms::none);
  if (::access(file.c_str(), R_OK) == 0) GTEST_SKIP() << "running as root: every file is readable";
  EXPECT_EQ(ErrorOfFile(file), file.string() + ": cannot open the file: Permission denied");
}

TEST_F(BodySpecTest, EmptyFileIsAnError) {
  EXPECT_EQ(ErrorOf(""), body() + ": the file is empty");
  EXPECT_EQ(ErrorOf("# only a comment\n"), body() + ": the file is empty");
}

TEST_F(BodySpecTest, MalformedYamlGivesLineAndColumn) {
  EXPECT_EQ(ErrorOf("name: beam\ngeometry: {file: beam.geo\nmaterials: x\n"),
            body() + ":3:10: malformed YAML: end of map flow not found");
  EXPECT_EQ(ErrorOf("name: beam\n  geometry: x\n"),
            body() + ":2:11: malformed YAML: illegal map value");
}

TEST_F(BodySpecTest, TopLevelMustBeAMap) {
  EXPECT_EQ(ErrorOf("- beam\n- steel\n"), body() + ":1:1: expected a map of keys at the top level");
}

// --- keys and types ---

TEST_F(BodySpecTest, UnknownTopLevelKeyIsNamedWithItsPosition) {
  ExpectStartsWith(ErrorOf(Replace(kValidBody, "name: beam", "nmae: beam")),
                   body() + ":1:1: nmae: unknown key 'nmae' (expected one of: name, geometry,");
}

TEST_F(BodySpecTest, UnknownNestedKeyIsNamedWithItsPath) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "mesh_size:", "mesh_sise:")),
            body() +
                ":4:3: geometry.mesh_sise: unknown key 'mesh_sise' (expected one of: file, "
                "mesh_size, element_order)");
  ExpectStartsWith(ErrorOf(Replace(kValidBody, "youngs_modulus", "young_modulus")),
                   body() + ":7:11: materials.steel.young_modulus: unknown key 'young_modulus'");
}

TEST_F(BodySpecTest, DuplicateKeyIsAnError) {
  EXPECT_EQ(ErrorOf(std::string(kValidBody) + "name: other\n"),
            body() + ":10:1: name: duplicate key 'name' (first at line 1)");
}

TEST_F(BodySpecTest, MissingRequiredKeyIsNamed) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "  file: beam.geo\n", "")),
            body() + ":3:3: geometry: missing key 'file'");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, " density: 7850", " density: ")),
            body() + ":7:10: materials.steel: missing key 'density'");
}

TEST_F(BodySpecTest, WrongTypesAreNamedWithTheValue) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "mesh_size: 0.01", "mesh_size: [1, 2]")),
            body() + ":4:14: geometry.mesh_size: expected a number");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "mesh_size: 0.01", "mesh_size: fine")),
            body() + ":4:14: geometry.mesh_size: 'fine' is not a finite number");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "element_order: 1", "element_order: two")),
            body() + ":5:18: geometry.element_order: 'two' is not an integer");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "element_order: 1", "element_order: 1.5")),
            body() + ":5:18: geometry.element_order: '1.5' is not an integer");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "2.1e11", "stiff")),
            body() + ":7:27: materials.steel.youngs_modulus: 'stiff' is not a finite number");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "2.1e11", ".inf")),
            body() + ":7:27: materials.steel.youngs_modulus: '.inf' is not a finite number");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "node_sets: [clamp, tip]", "node_sets: {clamp: 1}")),
            body() + ":9:12: node_sets: expected a list of names");
  EXPECT_EQ(ErrorOf("geometry: beam.geo\nmaterials: {}\n"),
            body() + ":1:11: geometry: expected a map");
}

// --- geometry ---

TEST_F(BodySpecTest, MissingGeometryFileIsNamedWithItsPosition) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "file: beam.geo", "file: nope.geo")),
            body() + ":3:9: geometry.file: 'nope.geo' does not exist (resolved to '" +
                (dir_ / "nope.geo").string() + "')");
}

TEST_F(BodySpecTest, GeometryFileThatIsADirectoryIsAnError) {
  fs::create_directories(dir_ / "meshes");
  ExpectStartsWith(ErrorOf(Replace(kValidBody, "file: beam.geo", "file: meshes")),
                   body() + ":3:9: geometry.file: 'meshes' is a directory");
}

TEST_F(BodySpecTest, NonPositiveMeshSizeIsAnError) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "mesh_size: 0.01", "mesh_size: -1")),
            body() + ":4:14: geometry.mesh_size: mesh size -1 m must be > 0");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "mesh_size: 0.01", "mesh_size: 0")),
            body() + ":4:14: geometry.mesh_size: mesh size 0 m must be > 0");
}

TEST_F(BodySpecTest, ElementOrderMustBeOneOrTwo) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "element_order: 1", "element_order: 3")),
            body() + ":5:18: geometry.element_order: element order 3 must be 1 or 2");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "element_order: 1", "element_order: 0")),
            body() + ":5:18: geometry.element_order: element order 0 must be 1 or 2");
}

// --- materials ---

TEST_F(BodySpecTest, NonPositiveYoungsModulusIsAnError) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "2.1e11", "-2e11")),
            body() + ": material 'steel': Young's modulus -2e+11 must be > 0");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "2.1e11", "0")),
            body() + ": material 'steel': Young's modulus 0 must be > 0");
}

TEST_F(BodySpecTest, PoissonRatioOutsideOpenIntervalIsAnError) {
  for (const std::string nu : {"-1", "-1.5", "0.5", "0.7"}) {
    EXPECT_EQ(ErrorOf(Replace(kValidBody, "poisson_ratio: 0.3", "poisson_ratio: " + nu)),
              body() + ": material 'steel': Poisson's ratio " + nu + " must be in (-1, 0.5)");
  }
  for (const std::string nu : {"-0.99", "0", "0.49"}) {
    EXPECT_EQ(ErrorOf(Replace(kValidBody, "poisson_ratio: 0.3", "poisson_ratio: " + nu)),
              "no error")
        << "nu = " << nu;
  }
}

TEST_F(BodySpecTest, NonPositiveDensityIsAnError) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "density: 7850", "density: 0")),
            body() + ": material 'steel': density 0 must be > 0");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "density: 7850", "density: -7850")),
            body() + ": material 'steel': density -7850 must be > 0");
}

TEST_F(BodySpecTest, UnknownMaterialIsNamed) {
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "material: steel", "material: stell")),
            body() + ":8:11: material: unknown material 'stell' (defined: steel)");
  EXPECT_EQ(ErrorOf(Replace(kValidBody, "material: steel", "regions: {beam: alu}")),
            body() + ":8:17: regions.beam: unknown material 'alu' (defined: steel)");
}

TEST_F(BodySpecTest, MaterialsMustBeDefinedAndAssigned) {
  EXPECT_EQ(ErrorOf("geometry: {file: beam.geo}\nmaterials: {}\n"),
            body() + ":2:12: materials: define at least one material");
  EXPECT_EQ(ErrorOf("geometry: {file: beam.geo}\nmaterials:\n"
                    "  a: {youngs_modulus: 1e9, poisson_ratio: 0.3, density: 1000}\n"
                    "  b: {youngs_modulus: 2e9, poisson_ratio: 0.3, density: 1000}\n"),
            body() +
                ":1:1: name the material of each region ('regions') or of the whole body "
                "('material')");
}

TEST_F(BodySpecTest, UnknownMassMatrixKindIsAnError) {
  EXPECT_EQ(ErrorOf(std::string(kValidBody) + "mass_matrix: diagonal\n"),
            body() + ":10:14: mass_matrix: 'diagonal' must be 'consistent' or 'lumped'");
}

// --- meshing a body: errors of the mesh name the body file too ---

// Two tetrahedra on physical volume "solid" with a physical surface "base".
const std::string kTwoTets = testing::ReadTestData("two_tets.msh");

constexpr char kTwoTetsBody[] = R"(geometry: {file: two_tets.msh}
materials: {steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}}
material: steel
node_sets: [base]
)";

std::string BuildError(const fs::path& body_file) {
  try {
    BuildBodyMesh(LoadBodySpec(body_file));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST_F(BodySpecTest, BodyMeshAssignsTheMaterial) {
  Write("two_tets.msh", kTwoTets);
  const Mesh mesh = BuildBodyMesh(LoadBodySpec(Write("body.yaml", kTwoTetsBody)));
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].region, "solid");
  EXPECT_EQ(mesh.blocks[0].material.name, "steel");
  EXPECT_EQ(mesh.node_sets.at("base"), (std::vector<int>{0, 1, 2}));
}

TEST_F(BodySpecTest, UnknownNodeSetNamesBodyAndMeshFiles) {
  Write("two_tets.msh", kTwoTets);
  const fs::path file = Write("body.yaml", Replace(kTwoTetsBody, "[base]", "[base, tip]"));
  EXPECT_EQ(BuildError(file), file.string() + ": " + (dir_ / "two_tets.msh").string() +
                                  ": node set 'tip': no physical group of that name (the file "
                                  "has: base, solid)");
}

TEST_F(BodySpecTest, UnknownRegionNamesBodyAndMeshFiles) {
  Write("two_tets.msh", kTwoTets);
  const fs::path file =
      Write("body.yaml", Replace(kTwoTetsBody, "material: steel", "regions: {beam: steel}"));
  EXPECT_EQ(BuildError(file), file.string() + ": regions: 'beam' is not a physical volume of " +
                                  (dir_ / "two_tets.msh").string() + " (it has: solid)");
}

}  // namespace
}  // namespace flexmbs::fem
