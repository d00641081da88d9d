// ParaView output (mbs/body_geometry.h, mbs/paraview_writer.h): a reduced beam at a known pose
// and modal state is drawn at the deformed FE node positions computed here from the mesh and
// the basis; a rigid body is a stick figure; the files are read back by VTK's own XML reader
// (Debian's python3-vtk9) and the collection by a strict XML parser; a writer killed mid-run
// leaves a valid collection of the samples it finished.
#include "mbs/paraview_writer.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "mbs/flexible_body.h"
#include "mbs/mode_selection.h"
#include "mbs/rigid_body.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/paraview_read_back.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;
using Eigen::Index;

// Positions are O(1) m sums of a few products of O(1) numbers: round-off ~1e-15 m.
constexpr double kPositionTolerance = 1e-12;

// VTK cell types (vtkCellType.h).
constexpr int kVtkLine = 3, kVtkTriangle = 5, kVtkQuad = 9, kVtkPolygon = 7;

class ParaviewWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt::format("flexmbs_paraview_{}_{}", info->name(), getpid());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  nlohmann::json ReadBack(const fs::path& pvd) const { return flexmbs::testing::ReadParaviewCollection(pvd, dir_); }
  fs::path dir_;
};

// The beam clamped at its root, with constraint and normal modes of its tip interface.
const std::vector<Index> kKeptModes = {0, 2, 6, 8};

// A system of a rigid arm (markers at known points of B) and the reduced beam, and a state of
// both with a general pose and modal coordinates.
struct TwoBodies {
  MultibodySystem system;
  Eigen::VectorXd y;
  Eigen::Vector3d p_WBo_W[2];
  Eigen::Matrix3d R_WB[2];
  Eigen::VectorXd q;
  std::vector<RigidBodyMarker> markers;
};

std::unique_ptr<TwoBodies> MakeTwoBodies() {
  auto s = std::make_unique<TwoBodies>();
  s->markers = {{"pin", Eigen::Vector3d(0.2, 0.0, 0.0), Eigen::Matrix3d::Identity()},
                {"tip", Eigen::Vector3d(1.0, -0.3, 0.25), Eigen::Matrix3d::Identity()}};
  s->system.AddBody(std::make_unique<RigidBody>("arm", 2.0, Eigen::Vector3d(0.5, 0, 0), Eigen::Matrix3d::Identity(),
                                                s->markers));
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  s->system.AddBody(std::make_unique<FlexibleBody>("beam", RestrictModes(fe.body, kKeptModes), false));
  s->y = s->system.NeutralState();
  s->p_WBo_W[0] = Eigen::Vector3d(-0.4, 1.1, 0.3);
  s->p_WBo_W[1] = Eigen::Vector3d(0.3, -1.2, 2.0);
  s->R_WB[0] = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  s->R_WB[1] = Eigen::AngleAxisd(-2.1, Eigen::Vector3d(0.3, -1, 0.5).normalized()).toRotationMatrix();
  s->q = Eigen::Vector4d(0.01, -0.02, 0.3, -0.2);
  for (int b = 0; b < 2; ++b) {
    const Eigen::Quaterniond e(s->R_WB[b]);
    Eigen::VectorXd x(7 + (b == 1 ? 4 : 0));
    x.head<7>() << s->p_WBo_W[b], e.w(), e.x(), e.y(), e.z();
    if (b == 1) x.tail(4) = s->q;
    s->system.SetBodyState(b, x, Eigen::VectorXd::Zero(x.size() - 1), s->y);
  }
  return s;
}

// The beam's FE node `node` at the state, from the mesh and the kept columns of the basis:
// p_WBo_W + R_WB (X_N + Phi_N q), and its elastic displacement R_WB Phi_N q.
std::pair<Eigen::Vector3d, Eigen::Vector3d> ExpectedBeamNode(const TwoBodies& s, int node) {
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  Eigen::Vector3d u_B = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < kKeptModes.size(); ++i) {
    u_B += fe.basis.Phi.block<3, 1>(3 * static_cast<Index>(node), kKeptModes[i]) * s.q(static_cast<Index>(i));
  }
  return {s.p_WBo_W[1] + s.R_WB[1] * (fe.mesh.nodes.col(node) + u_B), s.R_WB[1] * u_B};
}

Eigen::Vector3d Row(const nlohmann::json& rows, std::size_t k) {
  return {rows[k][0].get<double>(), rows[k][1].get<double>(), rows[k][2].get<double>()};
}

// The reduction's visual surface of the 6 x 2 x 2 hex8 beam is its whole boundary, outward:
// 2 (6 2 + 6 2 + 2 2) = 56 quadrilaterals through the 7 3 3 - 5 1 1 = 58 boundary nodes, of
// total area 2 (L b + L h + b h), each facing away from the box centre.
TEST_F(ParaviewWriterTest, ReducedBeamHasItsWholeBoundaryAsVisualSurface) {
  const testing::FeReducedBody& fe = testing::CraigBamptonBeam();
  const sid::VisualSurface& surface = fe.body.visual_surface;
  ASSERT_EQ(surface.face_sizes.size(), 56u);
  EXPECT_EQ(std::set<int>(surface.face_nodes.begin(), surface.face_nodes.end()).size(), 58u);
  const Eigen::Vector3d centre = fe.mesh.nodes.rowwise().mean();
  double area = 0.0;
  std::size_t first = 0;
  for (int size : surface.face_sizes) {
    ASSERT_EQ(size, 4);
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < size; ++k) {
      const Eigen::Vector3d v = fe.mesh.nodes.col(surface.face_nodes[first + static_cast<std::size_t>(k)]);
      const Eigen::Vector3d w = fe.mesh.nodes.col(surface.face_nodes[first + static_cast<std::size_t>((k + 1) % size)]);
      a += 0.5 * v.cross(w);
      centroid += v / size;
    }
    EXPECT_GT(a.dot(centroid - centre), 0.0) << "polygon at " << centroid.transpose() << " faces inward";
    area += a.norm();
    first += static_cast<std::size_t>(size);
  }
  const Eigen::Vector3d& d = testing::kBeamSize;
  EXPECT_NEAR(area, 2.0 * (d.x() * d.y() + d.x() * d.z() + d.y() * d.z()), kPositionTolerance);
  // Restricting the scene's modes keeps the surface (its displacement comes from the kept phi).
  EXPECT_EQ(RestrictModes(fe.body, kKeptModes).visual_surface.face_nodes, surface.face_nodes);
}

TEST_F(ParaviewWriterTest, FlexibleSurfaceIsTheDeformedNodesInW) {
  const auto s = MakeTwoBodies();
  const BodyGeometry beam = BodyDrawing(s->system.body(1)).At(s->system.BodyPositions(s->y, 1));
  const sid::VisualSurface& surface = testing::CraigBamptonBeam().body.visual_surface;
  ASSERT_EQ(beam.polygon_sizes, surface.face_sizes);
  ASSERT_EQ(beam.polygon_points.size(), surface.face_nodes.size());
  EXPECT_EQ(beam.p_WP_W.cols(), 58);
  EXPECT_TRUE(beam.vertex_points.empty() && beam.line_points.empty());
  double max_displacement = 0.0;
  for (std::size_t k = 0; k < surface.face_nodes.size(); ++k) {
    const auto [p_WN_W, u_N_W] = ExpectedBeamNode(*s, surface.face_nodes[k]);
    const Index point = beam.polygon_points[k];
    EXPECT_LT((beam.p_WP_W.col(point) - p_WN_W).norm(), kPositionTolerance) << "node " << surface.face_nodes[k];
    EXPECT_LT((beam.u_P_W.col(point) - u_N_W).norm(), kPositionTolerance) << "node " << surface.face_nodes[k];
    max_displacement = std::max(max_displacement, u_N_W.norm());
  }
  // The state deforms the beam visibly, so the check above is not of the rigid pose alone.
  EXPECT_GT(max_displacement, 1e-3);
}

TEST_F(ParaviewWriterTest, RigidBodyIsAStickFigureOfOriginAndMarkers) {
  const auto s = MakeTwoBodies();
  const BodyGeometry arm = BodyDrawing(s->system.body(0)).At(s->system.BodyPositions(s->y, 0));
  ASSERT_EQ(arm.p_WP_W.cols(), 3);
  EXPECT_LT((arm.p_WP_W.col(0) - s->p_WBo_W[0]).norm(), kPositionTolerance);
  for (Index k = 0; k < 2; ++k) {
    const Eigen::Vector3d expected = s->p_WBo_W[0] + s->R_WB[0] * s->markers[static_cast<std::size_t>(k)].p_BoM_B;
    EXPECT_LT((arm.p_WP_W.col(k + 1) - expected).norm(), kPositionTolerance);
  }
  EXPECT_EQ(arm.line_points, (std::vector<int>{0, 1, 0, 2}));
  EXPECT_TRUE(arm.u_P_W.isZero(0.0));
  // Without markers: the origin as a single vertex.
  const RigidBody lone("lone", 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  Eigen::VectorXd x(7);
  x << 1, 2, 3, 1, 0, 0, 0;
  const BodyGeometry point = BodyDrawing(lone).At(x);
  EXPECT_EQ(point.vertex_points, std::vector<int>{0});
  EXPECT_EQ(point.p_WP_W.col(0), Eigen::Vector3d(1, 2, 3));
}

// A body file of schema 2 has no visual surface: the beam is drawn as the stick figure of its
// nodes, the single-node marker "corner" at its FE node's deformed position.
TEST_F(ParaviewWriterTest, FlexibleBodyWithoutVisualSurfaceIsAStickFigureOfItsNodes) {
  const auto s = MakeTwoBodies();
  sid::ReducedBody data = RestrictModes(testing::CraigBamptonBeam().body, kKeptModes);
  data.visual_surface = {};
  const FlexibleBody beam("beam", data, false);
  const BodyGeometry figure = BodyDrawing(beam).At(s->system.BodyPositions(s->y, 1));
  ASSERT_EQ(figure.p_WP_W.cols(), 1 + static_cast<Index>(data.nodes.size()));
  EXPECT_LT((figure.p_WP_W.col(0) - s->p_WBo_W[1]).norm(), kPositionTolerance);
  EXPECT_EQ(figure.line_points.size(), 2 * data.nodes.size());
  for (std::size_t k = 0; k < data.nodes.size(); ++k) {
    if (data.nodes[k].name != "corner") continue;
    const auto [p_WN_W, u_N_W] = ExpectedBeamNode(*s, data.nodes[k].fe_nodes.at(0));
    EXPECT_LT((figure.p_WP_W.col(static_cast<Index>(k) + 1) - p_WN_W).norm(), kPositionTolerance);
    EXPECT_LT((figure.u_P_W.col(static_cast<Index>(k) + 1) - u_N_W).norm(), kPositionTolerance);
    EXPECT_GT(u_N_W.norm(), 1e-4);
    return;
  }
  FAIL() << "the beam has no node 'corner'";
}

// The files through VTK's reader: a block per body, named after it, and per cell its body and
// points at the positions computed here.
TEST_F(ParaviewWriterTest, VtkReadsEveryVertexAtItsWorldPosition) {
  const auto s = MakeTwoBodies();
  const fs::path pvd = dir_ / "run.pvd";
  {
    ParaviewWriter writer(s->system, pvd);
    ASSERT_TRUE(writer.Record(0.25, s->y));
  }
  const nlohmann::json samples = ReadBack(pvd);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0]["file"], "run_vtk/run_000000.vtm");
  EXPECT_EQ(samples[0]["time"], 0.25);
  const nlohmann::json& blocks = samples[0]["blocks"];
  ASSERT_EQ(blocks.size(), 2u);

  const nlohmann::json& arm = blocks[0];
  EXPECT_EQ(arm["name"], "arm");
  ASSERT_EQ(arm["points"].size(), 3u);
  ASSERT_EQ(arm["cells"].size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    const nlohmann::json& line = arm["cells"][c];
    ASSERT_EQ(line.size(), 3u);
    EXPECT_EQ(line[0], kVtkLine);
    EXPECT_EQ(arm["body_id"][c], 0);
    EXPECT_LT((Row(arm["points"], line[1]) - s->p_WBo_W[0]).norm(), kPositionTolerance);
    const Eigen::Vector3d marker = s->p_WBo_W[0] + s->R_WB[0] * s->markers[c].p_BoM_B;
    EXPECT_LT((Row(arm["points"], line[2]) - marker).norm(), kPositionTolerance);
  }

  const nlohmann::json& beam = blocks[1];
  EXPECT_EQ(beam["name"], "beam");
  const sid::VisualSurface& surface = testing::CraigBamptonBeam().body.visual_surface;
  ASSERT_EQ(beam["points"].size(), 58u);
  ASSERT_EQ(beam["cells"].size(), surface.face_sizes.size());
  std::size_t corner = 0;
  for (std::size_t c = 0; c < surface.face_sizes.size(); ++c) {
    const nlohmann::json& polygon = beam["cells"][c];
    EXPECT_TRUE(polygon[0] == kVtkQuad || polygon[0] == kVtkPolygon || polygon[0] == kVtkTriangle) << polygon[0];
    EXPECT_EQ(beam["body_id"][c], 1);
    ASSERT_EQ(polygon.size(), 1u + static_cast<std::size_t>(surface.face_sizes[c]));
    for (std::size_t k = 1; k < polygon.size(); ++k, ++corner) {
      const std::size_t point = polygon[k];
      const auto [p_WN_W, u_N_W] = ExpectedBeamNode(*s, surface.face_nodes[corner]);
      EXPECT_LT((Row(beam["points"], point) - p_WN_W).norm(), kPositionTolerance);
      EXPECT_LT((Row(beam["displacement"], point) - u_N_W).norm(), kPositionTolerance);
      EXPECT_NEAR(beam["magnitude"][point].get<double>(), u_N_W.norm(), kPositionTolerance);
    }
  }
}

TEST_F(ParaviewWriterTest, CollectionListsEveryWrittenSampleWithItsTime) {
  const auto s = MakeTwoBodies();
  const fs::path pvd = dir_ / "series.pvd";
  ParaviewWriter writer(s->system, pvd, 2);
  const std::vector<double> times = {0.0, 0.1, 0.2, 0.30000000000000004, 0.4};
  std::vector<bool> written;
  for (double t : times) written.push_back(writer.Record(t, s->y));
  EXPECT_EQ(written, (std::vector<bool>{true, false, true, false, true}));
  EXPECT_EQ(writer.samples(), 3);
  const nlohmann::json samples = ReadBack(pvd);
  ASSERT_EQ(samples.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(samples[k]["time"].get<double>(), times[2 * k]);
    EXPECT_EQ(samples[k]["file"], fmt::format("series_vtk/series_{:06d}.vtm", k));
  }
}

TEST_F(ParaviewWriterTest, NewRunReplacesTheSampleFilesOfAnOldOne) {
  const auto s = MakeTwoBodies();
  const fs::path pvd = dir_ / "again.pvd";
  {
    ParaviewWriter old_run(s->system, pvd);
    for (int k = 0; k < 3; ++k) old_run.Record(k, s->y);
  }
  std::ofstream(dir_ / "again_vtk" / "notes.txt") << "not ours: kept";
  std::ofstream(dir_ / "again_vtk" / "again_000003_0.vtp.tmp.999") << "left by a killed run";
  ParaviewWriter writer(s->system, pvd);
  writer.Record(0.0, s->y);
  const fs::path folder = dir_ / "again_vtk";
  EXPECT_TRUE(fs::exists(folder / "again_000000.vtm") && fs::exists(folder / "again_000000_1.vtp"));
  for (const char* old : {"again_000001.vtm", "again_000001_0.vtp", "again_000002.vtm", "again_000002_1.vtp",
                           "again_000003_0.vtp.tmp.999"}) {
    EXPECT_FALSE(fs::exists(folder / old)) << old;
  }
  EXPECT_TRUE(fs::exists(folder / "notes.txt"));
  EXPECT_EQ(ReadBack(pvd).size(), 1u);
}

// A writer killed (SIGKILL) while writing leaves a collection that VTK reads completely: every
// listed sample, and no partial file listed.
TEST_F(ParaviewWriterTest, KilledRunLeavesAValidCollectionOfItsFinishedSamples) {
  const auto s = MakeTwoBodies();
  const fs::path pvd = dir_ / "killed.pvd";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ParaviewWriter writer(s->system, pvd);
    for (long k = 0; k < 100000; ++k) writer.Record(1e-3 * static_cast<double>(k), s->y);
    _exit(0);
  }
  // Wait until a few samples are listed, then kill it in mid-stride.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  auto listed = [&] {
    std::ifstream in(pvd);
    std::stringstream text;
    text << in.rdbuf();
    const std::string t = text.str();
    long count = 0;
    for (std::size_t at = t.find("<DataSet"); at != std::string::npos; at = t.find("<DataSet", at + 1)) ++count;
    return count;
  };
  while (listed() < 5 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the writer ended before it was killed";
  const nlohmann::json samples = ReadBack(pvd);
  ASSERT_GE(samples.size(), 5u);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EXPECT_EQ(samples[k]["time"].get<double>(), 1e-3 * static_cast<double>(k));
    ASSERT_EQ(samples[k]["blocks"].size(), 2u);
    EXPECT_EQ(samples[k]["blocks"][1]["points"].size(), 58u);
  }
}

}  // namespace
}  // namespace flexmbs::mbs
