// contact/pcm/contact_element.h: a triangle pair's patch (area, volume, barycentre, pressure
// centre, moments of area, weights and their gradients) against an independent midpoint-rule
// integration over B's triangle of where A's triangle lies under it, on random pairs; and the
// cases that give no element.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "contact/pcm/contact_element.h"
#include "tests/support/random_draws.h"

namespace flexmbs::contact {
namespace {

/// The patch integrals by the midpoint rule on the n^2 sub-triangles of B's triangle: at each
/// midpoint x the depth delta of A's plane under it along n, kept if x - delta n lies in A's
/// triangle and 0 <= delta <= max_depth.
struct Integrals {
  double area = 0.0, volume = 0.0, depth_squared = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero(), depth_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();  ///< integral of x x^T dA
};
Integrals Integrate(const Eigen::Vector3d (&a)[3], const Eigen::Vector3d (&b)[3], double max_depth, int n) {
  const Eigen::Vector3d normal_B = (b[1] - b[0]).cross(b[2] - b[0]).normalized();
  const Eigen::Vector3d normal_A = (a[1] - a[0]).cross(a[2] - a[0]);
  const double cell = 0.5 * (b[1] - b[0]).cross(b[2] - b[0]).norm() / (n * n);
  const auto inside_A = [&](const Eigen::Vector3d& y) {
    for (int k = 0; k < 3; ++k) {
      if ((a[(k + 1) % 3] - a[k]).cross(y - a[k]).dot(normal_A) < 0.0) return false;
    }
    return true;
  };
  Integrals result;
  const auto sample = [&](double i, double j) {
    const Eigen::Vector3d x = b[0] + (i / n) * (b[1] - b[0]) + (j / n) * (b[2] - b[0]);
    const double delta = normal_A.dot(x - a[0]) / normal_A.dot(normal_B);
    if (delta < 0.0 || delta > max_depth || !inside_A(x - delta * normal_B)) return;
    result.area += cell;
    result.volume += cell * delta;
    result.depth_squared += cell * delta * delta;
    result.first_moment += cell * x;
    result.depth_moment += cell * delta * x;
    result.second_moment += cell * x * x.transpose();
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      sample(i + 1.0 / 3.0, j + 1.0 / 3.0);                         // the upright sub-triangle's centroid
      if (i + j + 1 < n) sample(i + 2.0 / 3.0, j + 2.0 / 3.0);  // the inverted one's
    }
  }
  return result;
}

TEST(PcmElement, RandomTrianglePairsMatchTheMidpointIntegrationOfTheirOverlap) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> planar(-1.0, 1.0), height(-0.35, 0.15), angle(-M_PI, M_PI);
  const double max_depth = 0.25;
  int elements = 0, depth_clipped = 0;
  double worst_first = 0.0, worst_second = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Vector3d offset = flexmbs::testing::DrawVector3(planar, rng);
    Eigen::Vector3d b[3] = {{-1.0, -0.8, 0.0}, {1.0, -0.6, 0.0}, {0.1, 0.9, 0.0}};  // normal +z
    Eigen::Vector3d a[3];
    for (auto& p : a) {
      const double x = planar(rng);
      const double y = planar(rng);
      p = Eigen::Vector3d(x, y, height(rng));
    }
    if ((a[1] - a[0]).cross(a[2] - a[0]).z() > 0.0) std::swap(a[1], a[2]);  // A faces B
    for (auto* p : {&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]}) *p = R * *p + offset;
    const std::optional<PcmElement> element = TriangleElement(a[0], a[1], a[2], b[0], b[1], b[2], max_depth);
    const Integrals reference = Integrate(a, b, max_depth, 1500);
    if (!element) {
      EXPECT_LT(reference.volume, 1e-6) << trial;
      continue;
    }
    ++elements;
    depth_clipped += (a[0] - b[0]).dot(R.col(2)) < -max_depth || (a[1] - b[0]).dot(R.col(2)) < -max_depth ||
                     (a[2] - b[0]).dot(R.col(2)) < -max_depth;
    // The midpoint rule with 1500^2 cells misplaces the cells cut by the patch's edges: measured
    // largest errors 2.7e-5 (area, of up to 0.72), 1.8e-6 (volume), 5.8e-5 (barycentre), 2.9e-5
    // (pressure centre).
    EXPECT_NEAR(element->area, reference.area, 3e-4) << trial;
    EXPECT_NEAR(element->volume, reference.volume, 2e-5) << trial;
    EXPECT_NEAR(element->depth, element->volume / element->area, 1e-15);
    EXPECT_NEAR(element->depth_squared, reference.depth_squared, 4e-6) << trial;  // measured 4.1e-7
    EXPECT_TRUE(element->normal_W.isApprox(R.col(2), 1e-14));
    if (reference.area > 0.05) {
      EXPECT_LT((element->barycentre_W - reference.first_moment / reference.area).norm(), 6e-4) << trial;
    }
    if (reference.volume > 0.01) {
      EXPECT_LT((element->pressure_centre_W - reference.depth_moment / reference.volume).norm(), 3e-4) << trial;
    }
    // The weights rebuild the pressure centre on B and the point of A under it.
    const Eigen::Vector3d on_B = element->weights_B(0) * b[0] + element->weights_B(1) * b[1] + element->weights_B(2) * b[2];
    const Eigen::Vector3d on_A = element->weights_A(0) * a[0] + element->weights_A(1) * a[1] + element->weights_A(2) * a[2];
    EXPECT_LT((on_B - element->pressure_centre_W).norm(), 1e-12);
    EXPECT_LT((on_A - element->pressure_centre_W).cross(element->normal_W).norm(), 1e-12) << "A's point lies under it";
    EXPECT_GE(element->weights_A.minCoeff(), -1e-12);
    EXPECT_GE(element->weights_B.minCoeff(), -1e-12);
    // The moments of area about the pressure centre.
    const Eigen::Vector3d& x_p = element->pressure_centre_W;
    const Eigen::Vector3d first = reference.first_moment - reference.area * x_p;
    const Eigen::Matrix3d second = reference.second_moment - x_p * reference.first_moment.transpose() -
                                   reference.first_moment * x_p.transpose() + reference.area * x_p * x_p.transpose();
    worst_first = std::max(worst_first, (element->first_moment_W - first).norm());
    worst_second = std::max(worst_second, (element->second_moment_W - second).norm());
    // The weights' gradients carry them along B's plane: at x = x_p + r the weights w + G r rebuild
    // x on B and the point of A under x.
    for (const Eigen::Vector3d& r : {Eigen::Vector3d(0.3, -0.2, 0.0), Eigen::Vector3d(-0.1, 0.4, 0.0)}) {
      const Eigen::Vector3d x = x_p + R * r;
      const Eigen::Vector3d w_B = element->weights_B + element->weight_gradients_B * (R * r);
      const Eigen::Vector3d w_A = element->weights_A + element->weight_gradients_A * (R * r);
      EXPECT_LT((w_B(0) * b[0] + w_B(1) * b[1] + w_B(2) * b[2] - x).norm(), 1e-12) << trial;
      EXPECT_LT((w_A(0) * a[0] + w_A(1) * a[1] + w_A(2) * a[2] - x).cross(element->normal_W).norm(), 1e-12) << trial;
      EXPECT_NEAR(w_A.sum() + w_B.sum(), 2.0, 1e-12);
    }
  }
  std::printf("[ numbers  ] moments of area about the pressure centre against the midpoint rule: first %.2e, second %.2e\n",
              worst_first, worst_second);
  // The midpoint rule's cells cut by the patch's edges (measured 2.6e-5, 3.5e-5).
  EXPECT_LT(worst_first, 3e-4);
  EXPECT_LT(worst_second, 3e-4);
  EXPECT_GT(elements, 20);  // the trials reach overlapping, disjoint and depth-clipped pairs
  EXPECT_GT(depth_clipped, 3);
}

TEST(PcmElement, ATriangleAboveBOrFacingAwayGivesNoElementAndAFlatOneUnderBIsAPrism) {
  const Eigen::Vector3d b0(0, 0, 0), b1(2, 0, 0), b2(0, 2, 0);
  // A inside B's prism at depth 0.1, facing down (clockwise seen from +z).
  const Eigen::Vector3d a0(0.2, 0.2, -0.1), a1(0.2, 0.8, -0.1), a2(0.8, 0.2, -0.1);
  const std::optional<PcmElement> prism = TriangleElement(a0, a1, a2, b0, b1, b2, 1.0);
  ASSERT_TRUE(prism);
  EXPECT_NEAR(prism->area, 0.18, 1e-15);
  EXPECT_NEAR(prism->volume, 0.018, 1e-15);
  EXPECT_TRUE(prism->pressure_centre_W.isApprox(Eigen::Vector3d(0.4, 0.4, 0.0), 1e-14));
  EXPECT_FALSE(TriangleElement(a0, a2, a1, b0, b1, b2, 1.0)) << "A facing away from B";
  const Eigen::Vector3d up(0, 0, 0.2);
  EXPECT_FALSE(TriangleElement(a0 + up, a1 + up, a2 + up, b0, b1, b2, 1.0)) << "A above B";
  EXPECT_FALSE(TriangleElement(a0, a1, a2, b0, b1, b2, 0.05)) << "A deeper than the depth searched";
}

}  // namespace
}  // namespace flexmbs::contact
