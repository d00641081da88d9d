#include "fem/quadrature.h"

#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

struct Point {
  double x, y, z, w;
};

QuadratureRule FromPoints(const std::vector<Point>& pts, int degree) {
  QuadratureRule rule{Eigen::Matrix3Xd(3, static_cast<Eigen::Index>(pts.size())),
                      Eigen::VectorXd(static_cast<Eigen::Index>(pts.size())), degree};
  for (std::size_t q = 0; q < pts.size(); ++q) {
    const auto i = static_cast<Eigen::Index>(q);
    rule.points.col(i) = Eigen::Vector3d(pts[q].x, pts[q].y, pts[q].z);
    rule.weights(i) = pts[q].w;
  }
  return rule;
}

// Fully symmetric orbits on the unit tetrahedron (barycentric permutations), weights for a
// reference volume of 1/6.
void TetOrbit4(double a, double w, std::vector<Point>* pts) {  // (a, b, b, b), b = (1-a)/3
  const double b = (1.0 - a) / 3.0;
  pts->push_back({b, b, b, w});
  pts->push_back({a, b, b, w});
  pts->push_back({b, a, b, w});
  pts->push_back({b, b, a, w});
}
void TetOrbit6(double a, double w, std::vector<Point>* pts) {  // (a, a, b, b), b = 1/2 - a
  const double b = 0.5 - a;
  pts->push_back({a, a, b, w});
  pts->push_back({a, b, a, w});
  pts->push_back({b, a, a, w});
  pts->push_back({a, b, b, w});
  pts->push_back({b, a, b, w});
  pts->push_back({b, b, a, w});
}

QuadratureRule Tet(int degree) {
  std::vector<Point> pts;
  if (degree <= 1) {
    pts.push_back({0.25, 0.25, 0.25, 1.0 / 6.0});
    return FromPoints(pts, 1);
  }
  if (degree == 2) {
    TetOrbit4(0.5854101966249685, 1.0 / 24.0, &pts);
    return FromPoints(pts, 2);
  }
  if (degree == 3) {
    // Witherden & Vincent (2015) 8-point rule, degree 3, positive weights (their [-1, 1]
    // tetrahedron mapped to the unit one: points (x + 1) / 2, weights / 8).
    TetOrbit4(0.01551009245085493963, 0.18162379004944980942 / 8.0, &pts);
    TetOrbit4(0.67585825030471418765, 0.15170954328388352391 / 8.0, &pts);
    return FromPoints(pts, 3);
  }
  // Walkington's 14-point rule, degree 5, positive weights.
  TetOrbit4(0.7217942490673264, 0.01224884051939366, &pts);
  TetOrbit4(0.06734224221009817, 0.01878132095300264, &pts);
  TetOrbit6(0.4544962958743504, 0.007091003462846911, &pts);
  return FromPoints(pts, 5);
}

// Triangle rules on the unit triangle (area 1/2).
std::vector<Point> Triangle(int degree) {
  if (degree <= 2) {
    const double w = 1.0 / 6.0;
    return {{1.0 / 6.0, 1.0 / 6.0, 0, w}, {2.0 / 3.0, 1.0 / 6.0, 0, w}, {1.0 / 6.0, 2.0 / 3.0, 0, w}};
  }
  // Dunavant's 6-point rule, degree 4.
  const double a1 = 0.445948490915965, w1 = 0.223381589678011 / 2.0;
  const double a2 = 0.091576213509771, w2 = 0.109951743655322 / 2.0;
  std::vector<Point> pts;
  for (const auto& [a, w] : {std::pair{a1, w1}, std::pair{a2, w2}}) {
    const double b = 1.0 - 2.0 * a;
    pts.push_back({a, a, 0, w});
    pts.push_back({b, a, 0, w});
    pts.push_back({a, b, 0, w});
  }
  return pts;
}

QuadratureRule Wedge(int triangle_degree, int gauss_points) {
  const QuadratureRule line = GaussLine(gauss_points);
  std::vector<Point> pts;
  for (const Point& t : Triangle(triangle_degree)) {
    for (Eigen::Index k = 0; k < line.weights.size(); ++k) {
      pts.push_back({t.x, t.y, line.points(0, k), t.w * line.weights(k)});
    }
  }
  return FromPoints(pts, std::min(triangle_degree, 2 * gauss_points - 1));
}

QuadratureRule Hex(int gauss_points) {
  const QuadratureRule line = GaussLine(gauss_points);
  std::vector<Point> pts;
  const Eigen::Index n = line.weights.size();
  for (Eigen::Index k = 0; k < n; ++k) {
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < n; ++i) {
        pts.push_back({line.points(0, i), line.points(0, j), line.points(0, k),
                       line.weights(i) * line.weights(j) * line.weights(k)});
      }
    }
  }
  return FromPoints(pts, 2 * gauss_points - 1);
}

QuadratureRule Rule(ElementType type, bool for_mass) {
  switch (type) {
    case ElementType::kTet4: return Tet(for_mass ? 2 : 1);
    case ElementType::kTet10:  // degree 3 for stiffness: see StiffnessRule in quadrature.h
      return Tet(for_mass ? 5 : 3);
    case ElementType::kHex8: return Hex(2);
    case ElementType::kHex20: return Hex(3);
    case ElementType::kWedge6: return Wedge(2, 2);
    case ElementType::kWedge15: return Wedge(4, 3);
  }
  throw InternalError("unknown element type");
}

template <bool kForMass>
const QuadratureRule& CachedRule(ElementType type) {
  static const std::array<QuadratureRule, std::size(kElementTraits)> kRules = [] {
    std::array<QuadratureRule, std::size(kElementTraits)> rules;
    for (const ElementTraits& t : kElementTraits) {
      rules[static_cast<std::size_t>(t.type)] = Rule(t.type, kForMass);
    }
    return rules;
  }();
  return kRules[static_cast<std::size_t>(type)];
}

}  // namespace

QuadratureRule GaussLine(int n) {
  std::vector<Point> pts;
  switch (n) {
    case 1: pts = {{0, 0, 0, 2.0}}; break;
    case 2: {
      const double x = 1.0 / std::sqrt(3.0);
      pts = {{-x, 0, 0, 1.0}, {x, 0, 0, 1.0}};
      break;
    }
    case 3: {
      const double x = std::sqrt(0.6);
      pts = {{-x, 0, 0, 5.0 / 9.0}, {0, 0, 0, 8.0 / 9.0}, {x, 0, 0, 5.0 / 9.0}};
      break;
    }
    case 4: {
      const double s = 2.0 / 7.0 * std::sqrt(6.0 / 5.0);
      const double x1 = std::sqrt(3.0 / 7.0 - s), x2 = std::sqrt(3.0 / 7.0 + s);
      const double w1 = (18.0 + std::sqrt(30.0)) / 36.0, w2 = (18.0 - std::sqrt(30.0)) / 36.0;
      pts = {{-x2, 0, 0, w2}, {-x1, 0, 0, w1}, {x1, 0, 0, w1}, {x2, 0, 0, w2}};
      break;
    }
    default: throw InternalError("GaussLine: 1 to 4 points supported, asked " + std::to_string(n));
  }
  return FromPoints(pts, 2 * n - 1);
}

const QuadratureRule& StiffnessRule(ElementType type) { return CachedRule<false>(type); }

const QuadratureRule& AffineStiffnessRule(ElementType type) {
  static const QuadratureRule kAffineTet10 = Tet(2);
  return type == ElementType::kTet10 ? kAffineTet10 : StiffnessRule(type);
}
const QuadratureRule& MassRule(ElementType type) { return CachedRule<true>(type); }

}  // namespace flexmbs::fem
