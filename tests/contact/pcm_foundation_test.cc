// contact/pcm: a rigid sphere (icospheres of rising level) pressed into a rigid flat through
// elastic layers against the closed-form foundation law F = c pi d^2 (R - d/3) and its energy
// c pi (R d^3/3 - d^4/12), with the convergence table printed; damping and friction against
// their closed forms on the same pair;
// the two-layer stiffness; bad layers and bad surfaces as one-line InputErrors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/pcm/bvh.h"
#include "contact/pcm/candidate_pairs.h"
#include "contact/pcm/contact_element.h"
#include "contact/pcm/foundation.h"
#include "contact/pcm/surface_checks.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

using flexmbs::testing::InputErrorMessage;
using testing::FlatGrid;
using testing::Icosphere;

constexpr double kRadius = 0.02;     // [m]
constexpr double kMaxDepth = 0.005;  // [m], the depth searched and the flat's tree's sweep

/// Two rubber-like layers, 10 MPa over 2 mm each: c = 1 / (2 h / E) = 2.5e9 N/m^3.
ElasticFoundation Law(double areal_damping = 0.0, double friction = 0.0) {
  const ElasticLayer layer{1e7, 2e-3};
  return MakeElasticFoundation(layer, "ball", layer, "flat", areal_damping, RegularisedCoulomb{friction, 1e-3});
}

/// The closed form: c times the volume of the spherical cap of depth d under the flat.
double FoundationForce(double c, double depth) { return c * M_PI * depth * depth * (kRadius - depth / 3.0); }
/// Its integral over the depth, the energy stored: c pi (R d^3 / 3 - d^4 / 12).
double FoundationEnergy(double c, double depth) {
  return c * M_PI * (kRadius * depth * depth * depth / 3.0 - depth * depth * depth * depth / 12.0);
}

/// The pair's elements: a sphere of kRadius with its lowest point `depth` under the flat z = 0.
struct SphereOnFlat {
  PolygonMesh sphere, flat;
  std::vector<PcmElement> elements;
  SphereOnFlat(int level, double depth)
      : sphere(Icosphere(Eigen::Vector3d(0.0, 0.0, kRadius - depth), kRadius, level)), flat(FlatGrid(0.03, 8, 0.0)) {
    elements = ContactElements(sphere, flat, CandidatePairs(Bvh(sphere), Bvh(flat, kMaxDepth)), kMaxDepth);
  }
  /// The load on the sphere moving at v_W (every vertex), the flat at rest, about the centre.
  PairLoad Load(const ElasticFoundation& law, const Eigen::Vector3d& v_W) const {
    const Eigen::Matrix3Xd v_sphere = v_W.replicate(1, sphere.vertices_W.cols());
    const Eigen::Matrix3Xd v_flat = Eigen::Matrix3Xd::Zero(3, flat.vertices_W.cols());
    const Eigen::Vector3d centre = sphere.vertices_W.rowwise().mean();
    return SumLoads(law, elements, sphere, v_sphere, flat, v_flat, centre);
  }
};

TEST(PcmFoundation, TwoLayersInSeriesGiveTheHarmonicStiffness) {
  const ElasticFoundation law =
      MakeElasticFoundation({2e9, 1e-3}, "steel coat", {1e7, 4e-3}, "rubber", 5.0, RegularisedCoulomb{0.3, 1e-3});
  EXPECT_DOUBLE_EQ(law.stiffness, 1.0 / (1e-3 / 2e9 + 4e-3 / 1e7));
  EXPECT_EQ(law.areal_damping, 5.0);
  EXPECT_EQ(law.friction.coefficient, 0.3);
}

TEST(PcmFoundation, SphereOnFlatForceConvergesToTheFoundationLawUnderRefinement) {
  const double depth = 1e-3;
  const ElasticFoundation law = Law();
  const double exact = FoundationForce(law.stiffness, depth);
  std::printf("sphere R = %g m pressed %g m into a flat, c = %g N/m^3, F_exact = %.6g N\n", kRadius, depth,
              law.stiffness, exact);
  std::printf("%6s %10s %10s %12s %12s %12s\n", "level", "triangles", "elements", "F [N]", "error", "energy error");
  double previous_error = 1.0, previous_energy_error = 1.0;
  for (int level = 2; level <= 6; ++level) {
    const SphereOnFlat pair(level, depth);
    const PairLoad load = pair.Load(law, Eigen::Vector3d::Zero());
    // The force is the energy's derivative by the depth (B flat): central differences over 2 um.
    const double h = 1e-6;
    const double dU_dd = (ElasticEnergy(law, SphereOnFlat(level, depth + h).elements) -
                          ElasticEnergy(law, SphereOnFlat(level, depth - h).elements)) / (2.0 * h);
    EXPECT_NEAR(dU_dd / load.force_W.z(), 1.0, 1e-6) << "level " << level;  // measured 3.2e-7 to 4.4e-7
    const double error = load.force_W.z() / exact - 1.0;
    const double energy_error = ElasticEnergy(law, pair.elements) / FoundationEnergy(law.stiffness, depth) - 1.0;
    std::printf("%6d %10zu %10zu %12.6g %12.3e %12.3e\n", level, pair.sphere.face_sizes.size(), pair.elements.size(),
                load.force_W.z(), error, energy_error);
    // Second order in the edge length: measured error ratios 3.6, 3.8, 4.0, 4.0 from level 2 to 6.
    EXPECT_GT(previous_error / std::abs(error), level >= 4 ? 3.5 : 1.0) << "level " << level;
    previous_error = std::abs(error);
    // The energy converges alike: measured ratios 3.4, 3.8, 4.0, 4.0.
    EXPECT_GT(previous_energy_error / std::abs(energy_error), level >= 4 ? 3.5 : 1.0) << "level " << level;
    previous_energy_error = std::abs(energy_error);
    EXPECT_NEAR(load.normal_force, load.force_W.z(), 1e-12 * exact);
    EXPECT_LT(load.force_W.head<2>().norm(), 1e-12 * exact) << "no friction: the force is normal";
  }
  EXPECT_LT(previous_error, 0.02);  // measured 1.85e-3 at level 6 (81920 triangles), 7.4e-3 at level 5
  EXPECT_LT(previous_energy_error, 0.02);  // measured 2.7e-3 at level 6
}

TEST(PcmFoundation, TheSweptTreeOfBMissesNoElementOfATiltedPair) {
  // The sphere on the flat, both turned off the axes: the elements from the trees' candidate
  // pairs are those of all face pairs.
  SphereOnFlat pair(4, 2e-3);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())).toRotationMatrix();
  pair.sphere.vertices_W = R * pair.sphere.vertices_W;
  pair.flat.vertices_W = R * pair.flat.vertices_W;
  std::vector<FacePair> all;
  for (int a = 0; a < static_cast<int>(pair.sphere.face_sizes.size()); ++a) {
    for (int b = 0; b < static_cast<int>(pair.flat.face_sizes.size()); ++b) all.push_back({a, b});
  }
  const std::vector<PcmElement> everything = ContactElements(pair.sphere, pair.flat, all, kMaxDepth);
  const std::vector<FacePair> candidates = CandidatePairs(Bvh(pair.sphere), Bvh(pair.flat, kMaxDepth));
  const std::vector<PcmElement> found = ContactElements(pair.sphere, pair.flat, candidates, kMaxDepth);
  ASSERT_GT(everything.size(), 100u);
  EXPECT_EQ(found.size(), everything.size());
  EXPECT_LT(candidates.size(), all.size() / 50);  // the sweep keeps the search local
  double volume_all = 0.0, volume_found = 0.0;
  for (const PcmElement& e : everything) volume_all += e.volume;
  for (const PcmElement& e : found) volume_found += e.volume;
  EXPECT_NEAR(volume_found, volume_all, 1e-15 * volume_all);
}

TEST(PcmFoundation, SphereOnFlatDampingAndFrictionFollowTheirClosedForms) {
  const double depth = 1e-3, speed = 0.1, mu = 0.4, eps = 1e-3, damping = 2e5;
  const SphereOnFlat pair(6, depth);
  const ElasticFoundation elastic = Law(), damped = Law(damping), rough = Law(0.0, mu);
  const double elastic_force = pair.Load(elastic, Eigen::Vector3d::Zero()).force_W.z();
  // Approaching at `speed`: every element adds d_A A speed; the patches tile the cap's disc of
  // radius^2 2 R d - d^2 (the polyhedron's disc is a little smaller: measured -1.0e-3).
  const PairLoad approaching = pair.Load(damped, Eigen::Vector3d(0.0, 0.0, -speed));
  const double disc = M_PI * (2.0 * kRadius * depth - depth * depth);
  EXPECT_NEAR((approaching.force_W.z() - elastic_force) / (damping * disc * speed), 1.0, 0.01);
  // Receding faster than c d / d_A = 12.5 m/s, every element's pressure is clipped at 0.
  EXPECT_EQ(pair.Load(damped, Eigen::Vector3d(0.0, 0.0, 20.0)).normal_force, 0.0);
  // Sliding along x: each element's friction is mu F_N v / sqrt(v^2 + eps^2) against the slip, so
  // the total is too; its moment about the centre is (R - d) times it about y, up to the normal
  // forces' moment (the pressure centre off the axis; the icosphere is symmetric about it under
  // the centre: measured 9.1e-16 R, and the friction moment then to 4.4e-16).
  const PairLoad sliding = pair.Load(rough, Eigen::Vector3d(speed, 0.0, 0.0));
  const double friction = mu * sliding.normal_force * speed / std::sqrt(speed * speed + eps * eps);
  EXPECT_NEAR(sliding.normal_force, elastic_force, 1e-12 * elastic_force);
  EXPECT_NEAR(sliding.force_W.x(), -friction, 1e-12 * friction);
  const PairLoad resting = pair.Load(elastic, Eigen::Vector3d::Zero());
  const double lever = resting.moment_W.norm() / resting.normal_force;  // the pressure centre's offset
  EXPECT_LT(lever, 1e-14 * kRadius);
  EXPECT_NEAR(sliding.moment_W.y(), (kRadius - depth) * friction, 1e-14 * kRadius * friction);
}

TEST(PcmFoundation, LoadDerivativesAreCentralDifferencesOfTheLoads) {
  const ElasticFoundation law = Law(2e5, 0.4);
  const Eigen::Vector3d v(0.002, -0.001, -0.01);  // slip of the order of eps: friction far from linear
  const double h = 1e-7;                          // [m/s], [m]
  SphereOnFlat pair(4, 1e-3);
  // By the velocity, element by element.
  double worst_velocity = 0.0;
  Eigen::Matrix3d d_displacement = Eigen::Matrix3d::Zero();
  for (const PcmElement& element : pair.elements) {
    const ElementLoad load = Evaluate(law, element, v);
    d_displacement += load.d_displacement;
    Eigen::Matrix3d central;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
      central.col(k) = (Evaluate(law, element, v + step).force_W - Evaluate(law, element, v - step).force_W) / (2.0 * h);
    }
    worst_velocity = std::max(worst_velocity, (load.d_velocity - central).norm() / central.norm());
  }
  // By moving the sphere (the patches' areas change too: summed over the elements of a flat B,
  // c A n^T is the exact derivative of c V).
  // Undamped: the area held is the damping's only approximation (its d_A v_N dA/du term).
  const ElasticFoundation undamped = Law(0.0, 0.4);
  d_displacement.setZero();
  for (const PcmElement& element : pair.elements) d_displacement += Evaluate(undamped, element, v).d_displacement;
  const auto total_force = [&](const Eigen::Vector3d& shift) {
    SphereOnFlat moved(4, 1e-3);
    moved.sphere.vertices_W.colwise() += shift;
    moved.elements = ContactElements(moved.sphere, moved.flat, CandidatePairs(Bvh(moved.sphere), Bvh(moved.flat, kMaxDepth)),
                                     kMaxDepth);
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (const PcmElement& element : moved.elements) force += Evaluate(undamped, element, v).force_W;
    return force;
  };
  Eigen::Matrix3d central;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
    central.col(k) = (total_force(step) - total_force(-step)) / (2.0 * h);
  }
  const double worst_displacement = (d_displacement - central).norm() / central.norm();
  std::printf("[ numbers  ] d_velocity %.3e, d_displacement %.3e (relative)\n", worst_velocity, worst_displacement);
  EXPECT_LT(worst_velocity, 9e-9);      // measured 8.8e-10 (the differences' round-off)
  EXPECT_LT(worst_displacement, 5e-9);  // measured 4.5e-10
}

TEST(PcmFoundation, NonPositiveLayerModulusOrThicknessIsAOneLineErrorNamingTheSurface) {
  const ElasticLayer good{1e7, 2e-3};
  const RegularisedCoulomb no_friction{0.0, 1e-3};
  EXPECT_EQ(InputErrorMessage([&] { MakeElasticFoundation({0.0, 2e-3}, "ball", good, "flat", 0.0, no_friction); }),
            "layer modulus of surface 'ball' 0 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([&] { MakeElasticFoundation(good, "ball", {1e7, -1e-3}, "flat", 0.0, no_friction); }),
            "layer thickness of surface 'flat' -0.001 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([&] { MakeElasticFoundation(good, "ball", {-5.0, 1e-3}, "flat", 0.0, no_friction); }),
            "layer modulus of surface 'flat' -5 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([&] { MakeElasticFoundation({1e7, 0.0}, "ball", good, "flat", 0.0, no_friction); }),
            "layer thickness of surface 'ball' 0 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([&] { MakeElasticFoundation(good, "ball", good, "flat", -1.0, no_friction); }),
            "areal damping -1 must be finite and >= 0");
}

TEST(PcmSurface, AFlippedTriangleAHoleAndAQuadAreOneLineErrorsNamingThem) {
  PolygonMesh sphere = Icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  EXPECT_EQ(InputErrorMessage([&] { RequirePcmSurface(sphere, "ball", true); }), "no error");
  double volume = 0.0;  // outward: the signed volume is +, 4/3 pi less the facets' sag
  for (std::size_t f = 0; f < sphere.face_sizes.size(); ++f) {
    const int* v = &sphere.face_vertices[3 * f];
    volume += sphere.vertices_W.col(v[0]).dot(sphere.vertices_W.col(v[1]).cross(sphere.vertices_W.col(v[2]))) / 6.0;
  }
  EXPECT_GT(volume, 0.9 * 4.0 / 3.0 * M_PI);
  PolygonMesh flipped = sphere;
  std::swap(flipped.face_vertices[3 * 17 + 1], flipped.face_vertices[3 * 17 + 2]);
  EXPECT_NE(InputErrorMessage([&] { RequirePcmSurface(flipped, "ball", false); })
                .find("inconsistent orientation (a flipped triangle)"),
            std::string::npos);
  EXPECT_NE(InputErrorMessage([&] { RequirePcmSurface(flipped, "ball", false); }).find("surface 'ball': triangles "),
            std::string::npos);
  PolygonMesh holed = sphere;
  holed.face_sizes.pop_back();
  holed.face_vertices.resize(holed.face_vertices.size() - 3);
  const std::string hole = InputErrorMessage([&] { RequirePcmSurface(holed, "ball", true); });
  EXPECT_NE(hole.find("surface 'ball': edge "), std::string::npos) << hole;
  EXPECT_NE(hole.find("has no neighbour: a hole in a surface that must be closed"), std::string::npos) << hole;
  EXPECT_EQ(InputErrorMessage([&] { RequirePcmSurface(holed, "ball", false); }), "no error");
  EXPECT_EQ(InputErrorMessage([&] { RequirePcmSurface(testing::Box(Eigen::Vector3d(1.0, 2.0, 3.0)), "block", true); }),
            "no error");
  const PolygonMesh flat = FlatGrid(1.0, 3, 0.0);
  EXPECT_EQ(InputErrorMessage([&] { RequirePcmSurface(flat, "floor", false); }), "no error");
  EXPECT_NE(InputErrorMessage([&] { RequirePcmSurface(flat, "floor", true); }).find("a hole"), std::string::npos);
  PolygonMesh quad;
  quad.vertices_W = Eigen::Matrix3Xd::Identity(3, 4);
  quad.face_sizes = {4};
  quad.face_vertices = {0, 1, 2, 3};
  EXPECT_EQ(InputErrorMessage([&] { RequirePcmSurface(quad, "lid", false); }),
            "surface 'lid': face 0 has 4 vertices; the polygonal contact model needs triangles");
  PolygonMesh degenerate = flat;
  degenerate.vertices_W.col(1) = degenerate.vertices_W.col(0);
  EXPECT_NE(InputErrorMessage([&] { RequirePcmSurface(degenerate, "floor", false); }).find("has no area"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::contact
