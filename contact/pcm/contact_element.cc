#include "contact/pcm/contact_element.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// A convex polygon in B's plane: vertices (u, v, delta), u and v along B's tangents, delta the
/// depth of A's triangle there. A triangle cut by five half-planes keeps at most 8 vertices.
struct Patch {
  std::array<Eigen::Vector3d, 8> vertices;
  int count = 0;
};

/// Keeps the part of `patch` where the linear function `side` >= 0 (Sutherland & Hodgman 1974:
/// one half-plane at a time), u, v and delta interpolated along the cut edges.
template <typename Side>
Patch Clip(const Patch& patch, Side side) {
  Patch kept;
  for (int k = 0; k < patch.count; ++k) {
    const Eigen::Vector3d& p = patch.vertices[k];
    const Eigen::Vector3d& q = patch.vertices[(k + 1) % patch.count];
    const double sp = side(p), sq = side(q);
    if (sp >= 0.0) kept.vertices[kept.count++] = p;
    if ((sp >= 0.0) != (sq >= 0.0)) kept.vertices[kept.count++] = p + sp / (sp - sq) * (q - p);
  }
  return kept;
}

/// Barycentric weights of the 2D point x in the triangle (p0, p1, p2).
Eigen::Vector3d Barycentric(const Eigen::Vector2d& x, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                            const Eigen::Vector2d& p2) {
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const double twice_area = cross(p1 - p0, p2 - p0);
  const double w1 = cross(x - p0, p2 - p0) / twice_area, w2 = cross(p1 - p0, x - p0) / twice_area;
  return {1.0 - w1 - w2, w1, w2};
}

/// The gradients of Barycentric's weights by x (row k: weight k's, 3 x 2).
Eigen::Matrix<double, 3, 2> BarycentricGradients(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                                                 const Eigen::Vector2d& p2) {
  const Eigen::Vector2d e1 = p1 - p0, e2 = p2 - p0;
  const double twice_area = e1.x() * e2.y() - e1.y() * e2.x();
  Eigen::Matrix<double, 3, 2> gradients;
  gradients.row(1) << e2.y() / twice_area, -e2.x() / twice_area;
  gradients.row(2) << -e1.y() / twice_area, e1.x() / twice_area;
  gradients.row(0) = -gradients.row(1) - gradients.row(2);
  return gradients;
}

}  // namespace

std::optional<PcmElement> TriangleElement(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                                          const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                                          double max_depth) {
  FLEXMBS_CHECK(max_depth > 0.0, "a PCM element needs max_depth > 0");
  const Eigen::Vector3d area_B = (b1 - b0).cross(b2 - b0), area_A = (a1 - a0).cross(a2 - a0);
  if (!(area_B.norm() > 0.0) || !(area_A.dot(area_B) < 0.0)) return std::nullopt;
  const Eigen::Vector3d n = area_B.normalized();
  const Eigen::Vector3d t1 = (b1 - b0).normalized(), t2 = n.cross(t1);
  const auto local = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d r = x - b0;
    return Eigen::Vector3d(r.dot(t1), r.dot(t2), -r.dot(n));
  };
  Patch patch;
  patch.count = 3;
  patch.vertices = {local(a0), local(a1), local(a2)};
  const Eigen::Vector3d corners[3] = {local(b0), local(b1), local(b2)};  // delta 0, counter-clockwise in (u, v)
  patch = Clip(patch, [](const Eigen::Vector3d& p) { return p.z(); });
  patch = Clip(patch, [&](const Eigen::Vector3d& p) { return max_depth - p.z(); });
  for (int k = 0; k < 3 && patch.count >= 3; ++k) {
    const Eigen::Vector2d from = corners[k].head<2>(), edge = corners[(k + 1) % 3].head<2>() - from;
    patch = Clip(patch, [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d r = p.head<2>() - from;
      return edge.x() * r.y() - edge.y() * r.x();
    });
  }
  if (patch.count < 3) return std::nullopt;
  // Fan from vertex 0: for linear f, g on a triangle of area s, integral(f g) = s/12 (sum f_i g_i
  // + sum f_i sum g_i); the areas carry the patch's orientation (clockwise: A faces B), fixed below.
  double area = 0.0, volume = 0.0, depth_squared = 0.0;
  Eigen::Vector2d first_moment = Eigen::Vector2d::Zero(), depth_moment = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second_moment = Eigen::Matrix2d::Zero();  // integral of x x^T dA about (u, v) = 0
  const Eigen::Vector3d& p0 = patch.vertices[0];
  for (int k = 1; k + 1 < patch.count; ++k) {
    const Eigen::Vector3d &p1 = patch.vertices[k], &p2 = patch.vertices[k + 1];
    const Eigen::Vector2d e1 = (p1 - p0).head<2>(), e2 = (p2 - p0).head<2>();
    const double s = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    const Eigen::Vector2d x_sum = (p0 + p1 + p2).head<2>();
    const double delta_sum = p0.z() + p1.z() + p2.z();
    area += s;
    volume += s * delta_sum / 3.0;
    depth_squared += s / 12.0 * (p0.z() * p0.z() + p1.z() * p1.z() + p2.z() * p2.z() + delta_sum * delta_sum);
    first_moment += s * x_sum / 3.0;
    second_moment += s / 12.0 *
                     (p0.head<2>() * p0.head<2>().transpose() + p1.head<2>() * p1.head<2>().transpose() +
                      p2.head<2>() * p2.head<2>().transpose() + x_sum * x_sum.transpose());
    depth_moment += s / 12.0 * (p0.z() * p0.head<2>() + p1.z() * p1.head<2>() + p2.z() * p2.head<2>() + delta_sum * x_sum);
  }
  if (!(volume / area > 0.0)) return std::nullopt;  // touching only, or a sliver with no area
  const Eigen::Vector2d barycentre = first_moment / area, pressure_centre = depth_moment / volume;
  PcmElement element;
  element.area = std::abs(area);
  element.volume = std::abs(volume);
  element.depth = element.volume / element.area;
  element.depth_squared = std::abs(depth_squared);
  element.normal_W = n;
  const auto world = [&](const Eigen::Vector2d& x) -> Eigen::Vector3d { return b0 + x.x() * t1 + x.y() * t2; };
  element.barycentre_W = world(barycentre);
  element.pressure_centre_W = world(pressure_centre);
  element.weights_B = Barycentric(pressure_centre, corners[0].head<2>(), corners[1].head<2>(), corners[2].head<2>());
  element.weights_A = Barycentric(pressure_centre, local(a0).head<2>(), local(a1).head<2>(), local(a2).head<2>());
  Eigen::Matrix<double, 3, 2> tangents;  // (u, v) to W
  tangents << t1, t2;
  element.weight_gradients_B =
      BarycentricGradients(corners[0].head<2>(), corners[1].head<2>(), corners[2].head<2>()) * tangents.transpose();
  element.weight_gradients_A =
      BarycentricGradients(local(a0).head<2>(), local(a1).head<2>(), local(a2).head<2>()) * tangents.transpose();
  // About the pressure centre, with the patch's orientation's sign taken out as for the area.
  const double sign = area < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector2d moment_p = sign * (first_moment - area * pressure_centre);
  const Eigen::Matrix2d inertia_p =
      sign * (second_moment - pressure_centre * first_moment.transpose() - first_moment * pressure_centre.transpose() +
              area * pressure_centre * pressure_centre.transpose());
  element.first_moment_W = tangents * moment_p;
  element.second_moment_W = tangents * inertia_p * tangents.transpose();
  return element;
}

std::vector<PcmElement> ContactElements(const PolygonMesh& A, const PolygonMesh& B, const std::vector<FacePair>& pairs,
                                        double max_depth) {
  FLEXMBS_CHECK(A.face_vertices.size() == 3 * A.face_sizes.size() && B.face_vertices.size() == 3 * B.face_sizes.size(),
                "PCM surfaces are triangle meshes");
  const auto vertex = [](const PolygonMesh& mesh, int face, int k) -> Eigen::Vector3d {
    return mesh.vertices_W.col(mesh.face_vertices[3 * face + k]);
  };
  std::vector<PcmElement> elements;
  for (const FacePair& pair : pairs) {
    std::optional<PcmElement> element =
        TriangleElement(vertex(A, pair.face_A, 0), vertex(A, pair.face_A, 1), vertex(A, pair.face_A, 2),
                        vertex(B, pair.face_B, 0), vertex(B, pair.face_B, 1), vertex(B, pair.face_B, 2), max_depth);
    if (!element) continue;
    element->face_A = pair.face_A;
    element->face_B = pair.face_B;
    elements.push_back(*element);
  }
  return elements;
}

}  // namespace flexmbs::contact
