// The Polygonal Contact Model's broad phase (docs/contact.md, "Polygonal Contact Model"): time
// per step for two deforming icospheres of 1.3e3 to 3.3e5 triangles each, flexmbs' AABB tree
// refitted (SAH), flexmbs' tree rebuilt (median and SAH splits), and FCL 0.7's BVHModel<AABB> refitted and BVHModel<OBBRSS>
// rebuilt, each followed by its tree-vs-tree query, on the same meshes in one run; then the
// degradation of a refitted tree against its query time, which sets the rebuild threshold; a
// whole PCM step (refit, pairs, elements, loads) on the same pair; and the force element on two
// reduced bodies' deforming surfaces (clamped plates of n x n x 1 hex8 cells, one turned over onto
// the other), its trees refitted against rebuilt, its broad phase against FCL's on the same meshes.
//
//   bench_pcm [levels, default 3,4,5,6,7] [plate cells n, default 16,32,64]
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/command_line.h"
#include "contact/pcm/bvh.h"
#include "contact/pcm/candidate_pairs.h"
#include "contact/pcm/contact_element.h"
#include "contact/pcm/foundation.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/pcm_surface.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/mbs/pcm_flexible_bodies.h"
#include "tests/support/test_problems.h"

namespace {

using flexmbs::contact::Bvh;
using flexmbs::contact::BvhSplit;
using flexmbs::contact::CandidatePairs;
using flexmbs::contact::PolygonMesh;
namespace testing = flexmbs::contact::testing;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The two surfaces at step k: unit icospheres `distance` apart (1.8: overlapping by 0.2), each
/// moved by a travelling wave of amplitude 0.01 (a flexible body's small deformation).
struct Scene {
  PolygonMesh rest_A, rest_B, A, B;
  explicit Scene(int level, double distance = 1.8)
      : rest_A(testing::Icosphere(Eigen::Vector3d::Zero(), 1.0, level)),
        rest_B(testing::Icosphere(Eigen::Vector3d(distance, 0.1, 0.05).normalized() * distance, 1.0, level)),
        A(rest_A),
        B(rest_B) {}
  void Step(int k, double amplitude = 0.01) {
    A.vertices_W = rest_A.vertices_W;
    B.vertices_W = rest_B.vertices_W;
    testing::Wave(A, amplitude, 6.0, 0.3 * k);
    testing::Wave(B, amplitude, 5.0, -0.2 * k);
  }
};

std::vector<fcl::Vector3d> Points(const PolygonMesh& mesh) {
  std::vector<fcl::Vector3d> points(mesh.vertices_W.cols());
  for (Eigen::Index v = 0; v < mesh.vertices_W.cols(); ++v) points[v] = mesh.vertices_W.col(v);
  return points;
}

template <typename Bv>
std::shared_ptr<fcl::BVHModel<Bv>> FclModel(const PolygonMesh& mesh) {
  std::vector<fcl::Triangle> triangles;
  for (std::size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    const int* v = &mesh.face_vertices[3 * f];
    triangles.emplace_back(v[0], v[1], v[2]);
  }
  auto model = std::make_shared<fcl::BVHModel<Bv>>();
  model->beginModel();
  model->addSubModel(Points(mesh), triangles);
  model->endModel();
  return model;
}

/// Refits FCL's model to the mesh's moved vertices (bottom-up).
template <typename Bv>
void FclRefit(fcl::BVHModel<Bv>& model, const PolygonMesh& mesh) {
  std::vector<fcl::Vector3d> points = Points(mesh);
  model.beginUpdateModel();
  model.updateSubModel(points);
  model.endUpdateModel(true, true);
}

/// FCL's collide of two models at rest in W: the number of intersecting triangle pairs (all of
/// them: the request asks for up to 1e9 contacts).
template <typename Bv>
std::size_t FclCollide(const std::shared_ptr<fcl::BVHModel<Bv>>& A, const std::shared_ptr<fcl::BVHModel<Bv>>& B) {
  const fcl::CollisionObjectd object_A(A, fcl::Transform3d::Identity()), object_B(B, fcl::Transform3d::Identity());
  const fcl::CollisionRequestd request(1000000000, false);
  fcl::CollisionResultd result;
  fcl::collide(&object_A, &object_B, request, result);
  return result.numContacts();
}

void CompareBroadPhases(const std::vector<int>& levels) {
  std::printf("broad phase per step, two deforming icospheres (seconds per step; ratios to flexmbs refit)\n");
  std::printf("%9s %9s %10s %10s %10s %10s %11s %12s %9s %9s %10s %10s\n", "triangles", "pairs", "fcl pairs", "refit",
              "rebuild", "rebuild", "fcl refit", "fcl rebuild", "median/", "SAH/", "fcl refit/", "fcl rebld/");
  std::printf("%9s %9s %10s %10s %10s %10s %11s %12s %9s %9s %10s %10s\n", "per body", "(boxes)", "(triangles)",
              "flexmbs", "median", "SAH", "AABB", "OBBRSS", "refit", "refit", "refit", "refit");
  for (const int level : levels) {
    Scene scene(level);
    const int steps = level >= 7 ? 5 : level >= 6 ? 10 : 40;
    Bvh tree_A(scene.A), tree_B(scene.B);
    auto fcl_A = FclModel<fcl::AABBd>(scene.A), fcl_B = FclModel<fcl::AABBd>(scene.B);
    std::size_t pairs = 0, fcl_pairs = 0;
    double refit = 0.0, rebuild = 0.0, sah_rebuild = 0.0, fcl_refit = 0.0, fcl_rebuild = 0.0;
    for (int k = 1; k <= steps; ++k) {
      scene.Step(k);
      auto start = std::chrono::steady_clock::now();
      tree_A.Refit(scene.A);
      tree_B.Refit(scene.B);
      pairs = CandidatePairs(tree_A, tree_B).size();
      refit += Seconds(start);

      start = std::chrono::steady_clock::now();
      const std::size_t rebuilt_pairs = CandidatePairs(Bvh(scene.A, 0.0, 2, BvhSplit::kMedian),
                                                       Bvh(scene.B, 0.0, 2, BvhSplit::kMedian)).size();
      rebuild += Seconds(start);
      if (rebuilt_pairs != pairs) std::printf("  refit and rebuild disagree: %zu != %zu pairs\n", pairs, rebuilt_pairs);

      start = std::chrono::steady_clock::now();
      CandidatePairs(Bvh(scene.A), Bvh(scene.B));  // the default: SAH
      sah_rebuild += Seconds(start);

      start = std::chrono::steady_clock::now();
      FclRefit(*fcl_A, scene.A);
      FclRefit(*fcl_B, scene.B);
      fcl_pairs = FclCollide(fcl_A, fcl_B);
      fcl_refit += Seconds(start);

      start = std::chrono::steady_clock::now();
      FclCollide(FclModel<fcl::OBBRSSd>(scene.A), FclModel<fcl::OBBRSSd>(scene.B));
      fcl_rebuild += Seconds(start);
    }
    refit /= steps;
    rebuild /= steps;
    sah_rebuild /= steps;
    fcl_refit /= steps;
    fcl_rebuild /= steps;
    std::printf("%9zu %9zu %10zu %10.3e %10.3e %10.3e %11.3e %12.3e %9.2f %9.2f %10.2f %10.2f\n",
                scene.A.face_sizes.size(), pairs, fcl_pairs, refit, rebuild, sah_rebuild, fcl_refit, fcl_rebuild,
                rebuild / refit, sah_rebuild / refit, fcl_refit / refit, fcl_rebuild / refit);
  }
}

/// A whole PCM step on a deforming pair pressed 0.02 into each other (1 % of the radius, a
/// foundation contact's order): both trees refitted (B's faces swept to the depth searched,
/// 0.05), the candidate pairs, the elements and their loads, timed part by part.
void FullStep(const std::vector<int>& levels) {
  constexpr double kMaxDepth = 0.05;
  const flexmbs::contact::ElasticFoundation law = flexmbs::contact::MakeElasticFoundation(
      {1e7, 1e-2}, "A", {1e7, 1e-2}, "B", 1e3, flexmbs::contact::RegularisedCoulomb{0.3, 1e-3});
  std::printf("\nwhole step, A pressing 0.02 into B (seconds per step)\n");
  std::printf("%9s %9s %9s %10s %10s %10s %10s %10s %9s\n", "triangles", "pairs", "elements", "refit", "pairs",
              "elements", "loads", "total", "steps/s");
  for (const int level : levels) {
    Scene scene(level, 1.98);
    const int steps = level >= 7 ? 5 : level >= 6 ? 10 : 40;
    Bvh tree_A(scene.A), tree_B(scene.B, kMaxDepth);
    const Eigen::Matrix3Xd v_A = Eigen::Matrix3Xd::Zero(3, scene.A.vertices_W.cols());
    const Eigen::Matrix3Xd v_B = Eigen::Matrix3Xd::Ones(3, scene.B.vertices_W.cols());
    double refit = 0.0, query = 0.0, narrow = 0.0, loads = 0.0;
    std::size_t num_pairs = 0, num_elements = 0;
    for (int k = 1; k <= steps; ++k) {
      scene.Step(k);
      auto start = std::chrono::steady_clock::now();
      tree_A.Refit(scene.A);
      tree_B.Refit(scene.B);
      refit += Seconds(start);
      start = std::chrono::steady_clock::now();
      const std::vector<flexmbs::contact::FacePair> pairs = CandidatePairs(tree_A, tree_B);
      query += Seconds(start);
      start = std::chrono::steady_clock::now();
      const auto elements = flexmbs::contact::ContactElements(scene.A, scene.B, pairs, kMaxDepth);
      narrow += Seconds(start);
      start = std::chrono::steady_clock::now();
      flexmbs::contact::SumLoads(law, elements, scene.A, v_A, scene.B, v_B, Eigen::Vector3d::Zero());
      loads += Seconds(start);
      num_pairs = pairs.size();
      num_elements = elements.size();
    }
    const double total = (refit + query + narrow + loads) / steps;
    std::printf("%9zu %9zu %9zu %10.3e %10.3e %10.3e %10.3e %10.3e %9.0f\n", scene.A.face_sizes.size(), num_pairs,
                num_elements, refit / steps, query / steps, narrow / steps, loads / steps, total, 1.0 / total);
  }
}

/// The fastest of `repeats` candidate-pair queries [s].
double QueryTime(const Bvh& A, const Bvh& B, int repeats) {
  double fastest = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    CandidatePairs(A, B);
    fastest = std::min(fastest, Seconds(start));
  }
  return fastest;
}

/// The query time of a refitted tree (SAH, the default) against rebuilt ones (SAH and median
/// splits) as the deformation grows; the fastest of 30 queries each.
void Degradation(int level) {
  std::printf("\nrefitted tree against rebuilt, %zu triangles per body: deformation amplitude, degradation, query times\n",
              Scene(level).A.face_sizes.size());
  std::printf("%10s %12s %12s %12s %12s %8s %12s\n", "amplitude", "degradation", "query refit", "query SAH",
              "query median", "ratio", "rebuild [s]");
  for (const double amplitude : {0.0, 0.01, 0.03, 0.1, 0.2, 0.4}) {
    Scene scene(level);
    Bvh tree_A(scene.A), tree_B(scene.B);
    scene.Step(3, amplitude);
    tree_A.Refit(scene.A);
    tree_B.Refit(scene.B);
    const double query_refit = QueryTime(tree_A, tree_B, 30);
    const auto start = std::chrono::steady_clock::now();
    const Bvh built_A(scene.A), built_B(scene.B);
    const double build = Seconds(start);
    const double query_built = QueryTime(built_A, built_B, 30);
    const double query_median = QueryTime(Bvh(scene.A, 0.0, 2, BvhSplit::kMedian), Bvh(scene.B, 0.0, 2, BvhSplit::kMedian), 30);
    std::printf("%10.3f %12.3f %12.3e %12.3e %12.3e %8.2f %12.3e\n", amplitude,
                0.5 * (tree_A.Degradation() + tree_B.Degradation()), query_refit, query_built, query_median,
                query_refit / query_built, build);
  }
}

constexpr double kPlateSide = 0.2, kPlateThickness = 0.01;  // [m]

/// A steel plate kPlateSide x kPlateSide x kPlateThickness of n x n x 1 hex8 cells clamped at its
/// four side faces, 6 fixed-interface modes, its top face the contact surface "top".
flexmbs::mbs::testing::ClampedBox SideClampedPlate(int n) {
  return flexmbs::mbs::testing::MakeClampedBox(
      "plate", Eigen::Vector3i(n, n, 1), Eigen::Vector3d(kPlateSide, kPlateSide, kPlateThickness),
      [](const flexmbs::fem::Mesh& mesh) { return flexmbs::mbs::testing::SideFaceNodes(mesh, kPlateSide, kPlateSide); },
      "top", [](const flexmbs::fem::Mesh& mesh) { return flexmbs::testing::NodesOnPlane(mesh, 2, kPlateThickness); },
      [](const flexmbs::fem::Mesh&) { return std::vector<int>(); }, 6);
}

/// The system's state with body `upper` turned over onto the lower plate (at the origin), 0.1 rad
/// about z and a third of a cell aside, its top face `interference` [m] into the lower's.
Eigen::VectorXd PressedPairState(const flexmbs::mbs::MultibodySystem& system, int upper, int n, double interference) {
  using Eigen::Vector3d;
  const Eigen::Matrix3d R_WU =
      (Eigen::AngleAxisd(0.1, Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI, Vector3d::UnitX())).toRotationMatrix();
  const Vector3d centre(0.5 * kPlateSide + kPlateSide / n / 3.0, 0.5 * kPlateSide + kPlateSide / n / 3.0, 0.0);
  const Vector3d p_WUo_W = centre - R_WU * Vector3d(0.5 * kPlateSide, 0.5 * kPlateSide, 0.0) +
                           Vector3d(0.0, 0.0, 2.0 * kPlateThickness - interference);
  Eigen::VectorXd y = system.NeutralState();
  Eigen::VectorXd x_upper = system.BodyPositions(y, upper);
  const Eigen::Quaterniond e(R_WU);
  x_upper.head<7>() << p_WUo_W, e.w(), e.x(), e.y(), e.z();
  system.SetBodyState(upper, x_upper, Eigen::VectorXd::Zero(system.body(upper).num_velocities()), y);
  return y;
}

/// Deforms both plates for step k: each mode 2e-5 m at most, phases moving; velocities 0.01.
void DeformPlates(const flexmbs::mbs::MultibodySystem& system, const flexmbs::mbs::testing::ClampedBox& box, int k,
                  Eigen::VectorXd& y) {
  for (int b = 0; b < system.num_bodies(); ++b) {
    Eigen::VectorXd x = system.BodyPositions(y, b);
    const Eigen::Index modes = system.body(b).num_modes();
    for (Eigen::Index j = 0; j < modes; ++j) {
      x(7 + j) = 2e-5 * std::sin(0.7 * k + 1.3 * j + b) / box.fe.basis.Phi.col(j).cwiseAbs().maxCoeff();
    }
    system.SetBodyState(b, x, 0.01 * Eigen::VectorXd::Ones(system.body(b).num_velocities()), y);
  }
}

/// Seconds per step of the flexible pair's parts, and the sizes of its last step.
struct FlexiblePairTimes {
  double refit = 0.0, rebuild = 0.0, broad = 0.0, fcl = 0.0;  ///< element refitted, rebuilt; our broad phase; FCL's
  std::size_t elements = 0, pairs = 0, fcl_pairs = 0;
};

/// Times `steps` steps of the pair: the force element's AddForces with its trees refitted and
/// rebuilt, and on the same placed meshes flexmbs' refit and query against FCL's AABB refit and
/// collide (step 0 builds the trees, untimed).
FlexiblePairTimes TimeFlexiblePair(const flexmbs::mbs::MultibodySystem& system,
                                   const flexmbs::mbs::testing::ClampedBox& box,
                                   const flexmbs::mbs::PcmContactForce& refitted,
                                   const flexmbs::mbs::PcmContactForce& rebuilt, Eigen::VectorXd y, int steps,
                                   double max_depth) {
  namespace mbs = flexmbs::mbs;
  FlexiblePairTimes times;
  std::unique_ptr<Bvh> tree_A, tree_B;
  std::shared_ptr<fcl::BVHModel<fcl::AABBd>> fcl_A, fcl_B;
  for (int k = 0; k <= steps; ++k) {
    DeformPlates(system, box, k, y);
    const mbs::PlacedPcmSurface A(system, refitted.A(), y), B(system, refitted.B(), y);
    Eigen::VectorXd h = Eigen::VectorXd::Zero(system.num_velocities());
    auto start = std::chrono::steady_clock::now();
    refitted.AddForces(0.0, system, y, h);
    const double refit_step = Seconds(start);
    start = std::chrono::steady_clock::now();
    rebuilt.AddForces(0.0, system, y, h);
    const double rebuild_step = Seconds(start);
    if (k == 0) {
      tree_A = std::make_unique<Bvh>(A.mesh());
      tree_B = std::make_unique<Bvh>(B.mesh(), max_depth);
      fcl_A = FclModel<fcl::AABBd>(A.mesh());
      fcl_B = FclModel<fcl::AABBd>(B.mesh());
      continue;
    }
    times.refit += refit_step / steps;
    times.rebuild += rebuild_step / steps;
    start = std::chrono::steady_clock::now();
    tree_A->Refit(A.mesh());
    tree_B->Refit(B.mesh());
    const std::vector<flexmbs::contact::FacePair> pairs = CandidatePairs(*tree_A, *tree_B);
    times.broad += Seconds(start) / steps;
    start = std::chrono::steady_clock::now();
    FclRefit(*fcl_A, A.mesh());
    FclRefit(*fcl_B, B.mesh());
    times.fcl_pairs = FclCollide(fcl_A, fcl_B);
    times.fcl += Seconds(start) / steps;
    times.pairs = pairs.size();
    times.elements = flexmbs::contact::ContactElements(A.mesh(), B.mesh(), pairs, max_depth).size();
  }
  return times;
}

/// Two side-clamped plates of n x n x 1 cells (their top faces, 2 n^2 triangles, the contact
/// surfaces), the upper turned over and pressing 0.1 mm into the lower, both deformed anew at every
/// step: the force element with its trees refitted against rebuilt, our broad phase against FCL's.
void FlexiblePair(const std::vector<int>& cells) {
  namespace mbs = flexmbs::mbs;
  constexpr double kInterference = 1e-4, kMaxDepth = 1e-3;
  const flexmbs::contact::ElasticLayer layer{1e8, 2e-3};
  std::printf("\nflexible pair, two deforming plates' top faces (seconds per step; ratios to the refitted element)\n");
  std::printf("%9s %6s %9s %9s %10s %11s %11s %8s %10s %10s %10s %9s\n", "triangles", "modes", "pairs", "fcl pairs",
              "elements", "refit elem.", "rebuild el.", "rebuild/", "refit+pairs", "fcl refit", "fcl/", "steps/s");
  for (const int n : cells) {
    const mbs::testing::ClampedBox box = SideClampedPlate(n);
    mbs::MultibodySystem system(Eigen::Vector3d::Zero());
    const int lower = system.AddBody(std::make_unique<mbs::FlexibleBody>("lower", box.fe.body, false));
    const int upper = system.AddBody(std::make_unique<mbs::FlexibleBody>("upper", box.fe.body, false));
    const Eigen::Index modes = system.body(lower).num_modes();
    const auto side = [&](int b) {
      return mbs::ModalPcmSurface(mbs::MarkerRef::OnBody(b, system.body(b).FindMarker(mbs::FlexibleBody::kOriginMarker)),
                                  box.fe.body.surfaces.at(0), modes, layer, false);
    };
    const flexmbs::contact::RegularisedCoulomb friction{0.3, 1e-3};
    const mbs::PcmContactForce refitted("press", side(upper), side(lower), 1e5, friction, kMaxDepth);
    const mbs::PcmContactForce rebuilt("press", side(upper), side(lower), 1e5, friction, kMaxDepth,
                                       mbs::PcmTreeUpdate::kRebuild);
    const FlexiblePairTimes t = TimeFlexiblePair(system, box, refitted, rebuilt,
                                                 PressedPairState(system, upper, n, kInterference), n >= 64 ? 10 : 30,
                                                 kMaxDepth);
    std::printf("%9zu %6ld %9zu %9zu %10zu %11.3e %11.3e %8.2f %10.3e %10.3e %10.2f %9.0f\n",
                box.fe.body.surfaces.at(0).face_sizes.size() * 2, static_cast<long>(modes), t.pairs, t.fcl_pairs,
                t.elements, t.refit, t.rebuild, t.rebuild / t.refit, t.broad, t.fcl, t.fcl / t.broad, 1.0 / t.refit);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<int> levels = argc > 1 ? flexmbs::bench::ParseIntList(argv[1]) : std::vector<int>{3, 4, 5, 6, 7};
  CompareBroadPhases(levels);
  Degradation(5);
  FullStep(levels);
  FlexiblePair(argc > 2 ? flexmbs::bench::ParseIntList(argv[2]) : std::vector<int>{16, 32, 64});
  return 0;
}
