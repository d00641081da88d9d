// Mesh import: hand-written meshes and geometries, good and bad. Every bad one is an
// InputError whose message is one line naming the file and what is wrong with it.
#include "fem/gmsh_import.h"
#include "tests/input_error.h"
#include "tests/test_data.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "fem/assembly.h"

namespace flexmbs::fem {
namespace {

namespace fs = std::filesystem;

// tests/data/two_tets.msh: two tetrahedra sharing the face 1-2-3 (z = 0) in MSH 4.1, in
// physical volume "solid", with the triangle 1-2-3 in physical surface "base"; element 3 is
// listed 1 3 2 5 (positive orientation). tests/data/inverted_tet.msh lists it 1 2 3 5: the
// same tetrahedron turned inside out, det J = -1.
const std::string kTwoTets = testing::ReadTestData("two_tets.msh");
const std::string kInvertedTet = testing::ReadTestData("inverted_tet.msh");

// One pyramid (gmsh type 7) in MSH 2.2, physical volume 1 "solid".
constexpr char kPyramid[] = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "solid"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.5 0.5 1
$EndNodes
$Elements
1
1 7 2 1 1 1 2 3 4 5
$EndElements
)";

// One 27-node hexahedron (gmsh type 12) in MSH 2.2, without physical groups.
std::string Hex27() {
  std::ostringstream text;
  text << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n27\n";
  for (int k = 0; k < 27; ++k) {
    text << k + 1 << ' ' << 0.5 * (k % 3) << ' ' << 0.5 * (k / 3 % 3) << ' ' << 0.5 * (k / 9)
         << '\n';
  }
  text << "$EndNodes\n$Elements\n1\n1 12 2 0 1";
  for (int k = 1; k <= 27; ++k) text << ' ' << k;
  text << "\n$EndElements\n";
  return text.str();
}

constexpr char kEmptyMesh[] = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
0 0 0 0
$EndNodes
$Elements
0 0 0 0
$EndElements
)";

// A 0.1 m cube with a physical volume and two physical faces.
constexpr char kCubeGeo[] = R"(SetFactory("OpenCASCADE");
a = 0.1;
Box(1) = {0, 0, 0, a, a, a};
Physical Volume("block") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, a + 1e-6, a + 1e-6, 1e-6};
Physical Surface("top") = Surface In BoundingBox{-1e-6, -1e-6, a - 1e-6, a + 1e-6, a + 1e-6, a + 1e-6};
)";

constexpr char kSquareGeo[] = R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
)";

// Line 2 lacks a comma.
constexpr char kSyntaxErrorGeo[] = "Point(1) = {0, 0, 0, 1};\nPoint(2) = {1, 0, 0 1};\n";

constexpr double kSteelDensity = 7850.0;  // kg/m^3
// Masses are sums of a few element integrals: round-off only.
constexpr double kMassRelativeTolerance = 1e-12;

class GmshImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("flexmbs_gmsh_import_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path Write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // The message of the InputError ImportMesh throws for `file`.
  static std::string ImportError(const fs::path& file, MeshingOptions options = {},
                                 const std::vector<std::string>& node_sets = {}) {
    return testing::InputErrorMessage([&] { ImportMesh(file, options, node_sets); });
  }

  fs::path dir_;
};

void ExpectStartsWith(const std::string& text, const std::string& prefix) {
  EXPECT_TRUE(text.starts_with(prefix))
      << "  actual: " << text << "\nexpected: " << prefix << "...";
}

void ExpectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos)
      << "  actual: " << text << "\nexpected to contain: " << part;
}

void SetMaterial(Mesh* mesh) {
  for (ElementBlock& block : mesh->blocks) {
    block.material = {"steel", 2.1e11, 0.3, kSteelDensity};
  }
}

// Total mass from a consistent mass matrix: the sum of all entries is 3 m.
double TotalMass(const Mesh& mesh) {
  return AssembleSystem(mesh, MassMatrixKind::kConsistent).mass.sum() / 3.0;
}

// --- valid meshes ---

TEST_F(GmshImportTest, TwoTetMeshKeepsRegionsTagsAndNodeSets) {
  Mesh mesh = ImportMesh(Write("two_tets.msh", kTwoTets), {}, {"base"});
  EXPECT_EQ(mesh.num_nodes(), 5);
  EXPECT_EQ(mesh.node_ids, (std::vector<std::size_t>{1, 2, 3, 4, 5}));
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].type, ElementType::kTet4);
  EXPECT_EQ(mesh.blocks[0].region, "solid");
  EXPECT_EQ(mesh.blocks[0].element_ids, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(mesh.node_sets.at("base"), (std::vector<int>{0, 1, 2}));
  SetMaterial(&mesh);
  // Two tetrahedra of volume 1/6 each.
  EXPECT_NEAR(TotalMass(mesh), kSteelDensity / 3.0, kMassRelativeTolerance * kSteelDensity);
}

TEST_F(GmshImportTest, GeoFileIsMeshedAtTheRequestedOrder) {
  Mesh mesh = ImportMesh(Write("cube.geo", kCubeGeo), {0.05, 2}, {"bottom", "top"});
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].type, ElementType::kTet10);
  EXPECT_EQ(mesh.blocks[0].region, "block");
  EXPECT_FALSE(mesh.node_sets.at("bottom").empty());
  EXPECT_FALSE(mesh.node_sets.at("top").empty());
  SetMaterial(&mesh);
  const double mass = kSteelDensity * 1e-3;  // a box meshes exactly: rho a^3
  EXPECT_NEAR(TotalMass(mesh), mass, 1e-9 * mass);
}

// --- elements ---

TEST_F(GmshImportTest, InvertedTetIsNamedWithItsNodes) {
  Mesh mesh = ImportMesh(Write("inverted.msh", kInvertedTet), {}, {});
  SetMaterial(&mesh);
  try {
    AssembleSystem(mesh, MassMatrixKind::kConsistent);
    FAIL() << "no error for an inverted element";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "region 'solid': tet4 element 3 with nodes [1, 2, 3, 5] has non-positive Jacobian "
              "determinant -1");
  }
}

TEST_F(GmshImportTest, PyramidIsNotSupported) {
  const fs::path file = Write("pyramid.msh", kPyramid);
  EXPECT_EQ(ImportError(file), file.string() +
                                   ": region 'solid': element 1 is a pyramid5 (gmsh type 7), which "
                                   "flexmbs does not support (supported: tet4, tet10, hex8, hex20, "
                                   "wedge6, wedge15)");
}

TEST_F(GmshImportTest, Hex27IsNotSupported) {
  const fs::path file = Write("hex27.msh", Hex27());
  ExpectStartsWith(ImportError(file),
                   file.string() +
                       ": region 'volume 1': element 1 is a hex27 (gmsh type 12), "
                       "which flexmbs does not support");
}

// --- meshes that are not solids ---

TEST_F(GmshImportTest, EmptyMeshIsAnError) {
  const fs::path file = Write("empty.msh", kEmptyMesh);
  EXPECT_EQ(ImportError(file),
            file.string() + ": the mesh has no elements; flexmbs needs a solid (3-D) mesh");
}

TEST_F(GmshImportTest, EmptyGeometryIsAnError) {
  const fs::path file = Write("empty.geo", "// nothing\n");
  EXPECT_EQ(ImportError(file),
            file.string() + ": the mesh has no elements; flexmbs needs a solid (3-D) mesh");
}

TEST_F(GmshImportTest, SurfaceOnlyGeometryIsAnError) {
  const fs::path file = Write("square.geo", kSquareGeo);
  const std::string message = ImportError(file, {0.5, 1});
  ExpectStartsWith(message, file.string() + ": the mesh is 2-D (");
  ExpectContains(message,
                 " surface elements, no volume elements); flexmbs needs a solid (3-D) mesh");
}

// --- node sets ---

TEST_F(GmshImportTest, UnknownNodeSetListsThePhysicalGroups) {
  const fs::path file = Write("two_tets.msh", kTwoTets);
  EXPECT_EQ(ImportError(file, {}, {"base", "tip"}),
            file.string() +
                ": node set 'tip': no physical group of that name (the file has: base, solid)");
}

// --- files ---

TEST_F(GmshImportTest, MissingFileIsNamed) {
  const fs::path file = dir_ / "absent.geo";
  EXPECT_EQ(ImportError(file), file.string() + ": no such file");
}

TEST_F(GmshImportTest, DirectoryIsNotAMeshFile) {
  fs::create_directories(dir_ / "mesh.msh");
  EXPECT_EQ(ImportError(dir_ / "mesh.msh"),
            (dir_ / "mesh.msh").string() + ": is a directory, not a geometry or mesh file");
}

TEST_F(GmshImportTest, UnreadableFileIsNamed) {
  const fs::path file = Write("two_tets.msh", kTwoTets);
  fs::permissions(file, fs::perms::none);
  if (::access(file.c_str(), R_OK) == 0) GTEST_SKIP() << "running as root: every file is readable";
  EXPECT_EQ(ImportError(file), file.string() + ": cannot open the file: Permission denied");
}

TEST_F(GmshImportTest, UnknownExtensionIsAnError) {
  const fs::path file = Write("beam.txt", "");
  EXPECT_EQ(
      ImportError(file),
      file.string() + ": unsupported geometry file type '.txt' (use .geo, .step, .stp or .msh)");
}

TEST_F(GmshImportTest, ElementOrderThreeIsAnError) {
  const fs::path file = Write("cube.geo", kCubeGeo);
  EXPECT_EQ(ImportError(file, {0.05, 3}), file.string() + ": element order 3 must be 1 or 2");
}

// gmsh 4.8 throws out of its .geo parser by default and then ignores every later file
// ("I'm busy!"): the import must report the error and leave gmsh usable.
TEST_F(GmshImportTest, GeoSyntaxErrorGivesTheLineAndLeavesGmshUsable) {
  const fs::path bad = Write("syntax.geo", kSyntaxErrorGeo);
  EXPECT_EQ(ImportError(bad),
            bad.string() + ": gmsh could not read the file: line 2: syntax error (1)");
  const Mesh mesh = ImportMesh(Write("cube.geo", kCubeGeo), {0.05, 1}, {"top"});
  EXPECT_GT(mesh.num_elements(), 0);
}

TEST_F(GmshImportTest, GarbageMeshFileIsOneLineError) {
  const fs::path file =
      Write("garbage.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n");
  ExpectStartsWith(ImportError(file), file.string() + ": gmsh could not read the file: ");
}

TEST_F(GmshImportTest, ElementWithUnknownNodeIsAnError) {
  std::string text = kTwoTets;
  text.replace(text.find("3 1 3 2 5"), 9, "3 1 3 2 9");
  const fs::path file = Write("unknown_node.msh", text);
  ExpectStartsWith(ImportError(file),
                   file.string() + ": gmsh could not read the file: Unknown node 9 in element 3");
}

// OpenCASCADE prints STEP parse errors to stdout by itself: none of it may reach the terminal.
TEST_F(GmshImportTest, BadStepFileIsOneLineErrorAndPrintsNothing) {
  const fs::path file = Write("garbage.step", "this is not STEP\n");
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const std::string message = ImportError(file);
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(message, file.string() + ": gmsh could not read the file: Could not read file '" +
                         file.string() + "'");
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

}  // namespace
}  // namespace flexmbs::fem
