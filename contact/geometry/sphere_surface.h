#pragma once
// A sphere or a point against a polygon mesh (docs/contact.md, "Flexible bodies"): the mesh point
// nearest the sphere's centre or the point, found face by face, and the vertices and weights that
// move it, so a deforming mesh (a reduced body's contact surface) can give the point's velocity.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "contact/geometry/point_contact.h"

namespace flexmbs::contact {

/// The point of triangle (a, b, c) nearest to p [m], its barycentric weights (point = w0 a +
/// w1 b + w2 c, w >= 0, sum 1) and whether it lies inside the triangle rather than on an edge or
/// vertex (Ericson, "Real-Time Collision Detection", 2005, §5.1.5).
struct TrianglePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  bool interior = false;
};
TrianglePoint NearestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c);

/// The point of the bilinear quad X(xi, eta) = (1 - xi)(1 - eta) P0 + xi (1 - eta) P1 + xi eta P2 +
/// (1 - xi) eta P3 nearest to p [m], its four weights (the bilinear shape functions at (xi, eta),
/// or two on an edge, one at a vertex) and whether it lies inside the quad. Inside: Gauss-Newton
/// on |X - p|^2 from the centre; where the minimum is outside [0, 1]^2, the nearest point of the
/// four edges.
struct QuadPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< inside: dX/dxi x dX/deta, normalised
  bool interior = false;
};
QuadPoint NearestPointOnQuad(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 4>& P);

/// A polygon mesh in W: vertex positions (3 x V) [m], faces of 3 (flat triangles) or 4 (bilinear
/// quads) vertices counter-clockwise seen from outside.
struct PolygonMesh {
  Eigen::Matrix3Xd vertices_W;
  std::vector<int> face_sizes;
  std::vector<int> face_vertices;  ///< concatenated, 0-based into vertices_W
};

/// The face point of a mesh nearest to a point: the vertices and weights that move it (a
/// triangle's fourth weight 0), its face's outward normal there, and whether it lies inside the
/// face rather than on its rim.
struct MeshPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::array<int, 4> vertices{0, 0, 0, 0};
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  bool interior = false;
};

/// The point of one face of `mesh` nearest to p [m]: the face of `size` (3 or 4) vertices whose
/// indices start at face_vertices[first]. Preconditions (InternalError): 3 or 4 valid vertices.
MeshPoint NearestFacePoint(const Eigen::Vector3d& p, const PolygonMesh& mesh, std::size_t first, int size);

/// The face point of `mesh` nearest to p [m] over all faces (the first of equals): O(faces);
/// contact/pcm/nearest_face.h finds the same point through a bounding-volume hierarchy.
/// Preconditions (InternalError): faces of 3 or 4 valid vertices, at least one.
MeshPoint NearestMeshPoint(const Eigen::Vector3d& p, const PolygonMesh& mesh);

/// The point contact of sphere A on mesh B and where B's contact point lies: p_WB_W = sum_i
/// weights_i vertices_W(:, vertices_i) (a triangle's fourth weight is 0).
struct SphereMeshContact : PointContactKinematics {
  std::array<int, 4> vertices{0, 0, 0, 0};
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();
};

/// Sphere A against mesh B: the face point c nearest to the centre p_S over all faces (the first
/// of equals). Inside a face the normal is the face's outward normal there and
/// g_N = n . (p_S - c) - r; on an edge or vertex n = (p_S - c) / |p_S - c| and g_N = |p_S - c| - r.
/// p_WA_W = p_S - r n, p_WB_W = c. Meant for a centre outside the body (penetrations well below
/// r, as compliant and unilateral contact keep them). Throws DegenerateContactError if the
/// centre lies on an edge or vertex (no normal). Preconditions (InternalError): radius > 0, a
/// mesh with faces of 3 or 4 valid vertices.
SphereMeshContact SphereMesh(const Sphere& sphere, const PolygonMesh& mesh);

/// Node-to-surface: point A (a vertex of another body's surface) at p_WA_W against mesh B: the
/// nearest face point c (NearestMeshPoint) with its face's normal n and g_N = n . (p - c) where
/// p lies inside the face's prism or on its rim's normal line (|n . (p - c)| >= (1 - 1e-9)
/// |p - c|: a node level with the face's edge, as where two meshes' nodes meet); elsewhere p is off
/// the surface and n = (p - c) / |p - c|, g_N = |p - c| > 0. p_WB_W = c.
SphereMeshContact PointMesh(const Eigen::Vector3d& p_WA_W, const PolygonMesh& mesh);
/// PointMesh with the nearest face point already found (`nearest`, NearestMeshPoint's of p_WA_W).
SphereMeshContact PointMeshAt(const Eigen::Vector3d& p_WA_W, const MeshPoint& nearest);

}  // namespace flexmbs::contact
