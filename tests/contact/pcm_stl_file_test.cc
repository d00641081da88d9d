// contact::ReadStlFile: ASCII and binary STL files written by the test (a box, a tetrahedron)
// come back as the same closed, consistently oriented triangle meshes (coincident corners
// merged), whose enclosed volume is the solid's; truncated, malformed, empty, non-finite and
// missing files are one-line InputErrors naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "contact/pcm/stl_file.h"
#include "contact/pcm/surface_checks.h"
#include "core/error.h"
#include "tests/support/stl_writer.h"

namespace flexmbs::contact {
namespace {

namespace fs = std::filesystem;
using testing::StlTriangle;

/// The volume a closed mesh encloses, by the divergence theorem: sum of a . (b x c) / 6.
double EnclosedVolume(const PolygonMesh& mesh) {
  double volume = 0.0;
  for (std::size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    const int* v = &mesh.face_vertices[3 * f];
    volume += mesh.vertices_W.col(v[0]).dot(mesh.vertices_W.col(v[1]).cross(mesh.vertices_W.col(v[2]))) / 6.0;
  }
  return volume;
}

class StlFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("flexmbs_stl_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  /// The one-line message ReadStlFile throws for `file`.
  std::string ErrorOf(const fs::path& file) {
    try {
      ReadStlFile(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  fs::path dir_;
};

TEST_F(StlFileTest, ABoxInAsciiAndBinaryIsTheSameClosedMeshWithItsVolume) {
  const Eigen::Vector3d half(0.5, 0.25, 0.125), centre(1.0, -2.0, 0.5);  // exact in float
  const std::vector<StlTriangle> box = testing::BoxTriangles(half, centre);
  testing::WriteAsciiStl(dir_ / "box_ascii.stl", box);
  testing::WriteBinaryStl(dir_ / "box_binary.stl", box, "solid but binary");
  for (const char* name : {"box_ascii.stl", "box_binary.stl"}) {
    SCOPED_TRACE(name);
    const PolygonMesh mesh = ReadStlFile(dir_ / name);
    ASSERT_EQ(mesh.face_sizes.size(), 12u);
    EXPECT_EQ(mesh.vertices_W.cols(), 8) << "the 36 corners merged into the box's 8 vertices";
    EXPECT_NO_THROW(RequirePcmSurface(mesh, name, true));
    for (std::size_t f = 0; f < 12; ++f) {  // the triangles as written, corner by corner
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(mesh.vertices_W.col(mesh.face_vertices[3 * f + c]), box[f][static_cast<std::size_t>(c)]);
      }
    }
    EXPECT_DOUBLE_EQ(EnclosedVolume(mesh), 8.0 * half.prod());
  }
}

TEST_F(StlFileTest, ATetrahedronIsClosedAndAFlippedTriangleIsFoundThroughTheMergedVertices) {
  std::vector<StlTriangle> tetrahedron = testing::TetrahedronTriangles(0.75);
  testing::WriteBinaryStl(dir_ / "tet.stl", tetrahedron);
  const PolygonMesh mesh = ReadStlFile(dir_ / "tet.stl");
  EXPECT_EQ(mesh.vertices_W.cols(), 4);
  EXPECT_NO_THROW(RequirePcmSurface(mesh, "tet.stl", true));
  EXPECT_DOUBLE_EQ(EnclosedVolume(mesh), 0.75 * 0.75 * 0.75 / 6.0);
  std::swap(tetrahedron[3][1], tetrahedron[3][2]);
  testing::WriteAsciiStl(dir_ / "flipped.stl", tetrahedron);
  EXPECT_THROW(RequirePcmSurface(ReadStlFile(dir_ / "flipped.stl"), "flipped.stl", true), InputError);
  tetrahedron.pop_back();
  testing::WriteAsciiStl(dir_ / "open.stl", tetrahedron);
  EXPECT_NO_THROW(RequirePcmSurface(ReadStlFile(dir_ / "open.stl"), "open.stl", false));
  EXPECT_THROW(RequirePcmSurface(ReadStlFile(dir_ / "open.stl"), "open.stl", true), InputError);
}

TEST_F(StlFileTest, BadFilesAreOneLineErrorsNamingTheFile) {
  const std::vector<StlTriangle> tetrahedron = testing::TetrahedronTriangles(1.0);
  const auto expect = [&](const fs::path& file, const std::string& part) {
    const std::string message = ErrorOf(file);
    SCOPED_TRACE(message);
    EXPECT_NE(message.find("STL file '" + file.string() + "'"), std::string::npos);
    EXPECT_NE(message.find(part), std::string::npos);
    EXPECT_EQ(message.find('\n'), std::string::npos);
  };
  expect(dir_ / "missing.stl", "cannot be read");

  testing::WriteBinaryStl(dir_ / "truncated.stl", tetrahedron);
  fs::resize_file(dir_ / "truncated.stl", 84 + 50 * 4 - 7);
  expect(dir_ / "truncated.stl", "truncated: 4 triangles need 284 bytes, the file has 277");
  fs::resize_file(dir_ / "truncated.stl", 40);
  expect(dir_ / "truncated.stl", "40 bytes: truncated");

  testing::WriteAsciiStl(dir_ / "syntax.stl", tetrahedron);
  std::string text;
  {
    std::ifstream in(dir_ / "syntax.stl");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::string broken = text;
  broken.replace(broken.find("vertex"), 6, "vertx");  // line 4
  std::ofstream(dir_ / "syntax.stl") << broken;
  expect(dir_ / "syntax.stl", "line 4: unexpected (got '      vertx 0 0 0')");
  broken = text;
  broken.replace(broken.find("vertex 0 1 0"), 12, "vertex 0 1 x");
  std::ofstream(dir_ / "syntax.stl") << broken;
  expect(dir_ / "syntax.stl", "line 5: expected 'vertex x y z'");
  std::ofstream(dir_ / "syntax.stl") << text.substr(0, text.find("endsolid"));
  expect(dir_ / "syntax.stl", "ends inside a solid or facet");

  std::ofstream(dir_ / "empty_ascii.stl") << "solid nothing\nendsolid nothing\n";
  expect(dir_ / "empty_ascii.stl", "no triangles");
  testing::WriteBinaryStl(dir_ / "empty_binary.stl", {});
  expect(dir_ / "empty_binary.stl", "no triangles");

  broken = text;
  broken.replace(broken.find("vertex 0 1 0"), 12, "vertex 0 nan 0");
  std::ofstream(dir_ / "nan.stl") << broken;
  expect(dir_ / "nan.stl", "triangle 0 has a non-finite coordinate (0, nan, 0)");
  std::vector<StlTriangle> infinite = tetrahedron;
  infinite[2][1].x() = std::numeric_limits<double>::infinity();
  testing::WriteBinaryStl(dir_ / "inf.stl", infinite);
  expect(dir_ / "inf.stl", "triangle 2 has a non-finite coordinate (inf, 0, 1)");
}

}  // namespace
}  // namespace flexmbs::contact
