#pragma once
// The face point of a polygon mesh nearest to a point, found through the mesh's bounding-volume
// hierarchy (docs/contact.md, "Flexible bodies": surface_surface's node-to-surface search):
// branch and bound over the boxes, O(log faces) per point on a surface against O(faces) by
// contact::NearestMeshPoint, with the same answer.

#include <Eigen/Core>

#include "contact/geometry/sphere_surface.h"
#include "contact/pcm/bvh.h"

namespace flexmbs::contact {

/// The face point of `mesh` nearest to p [m], the same as NearestMeshPoint(p, mesh) (the first of
/// equals: faces compared by distance, then by index): `tree` is a Bvh built or refitted on `mesh`
/// as it is now (any depth: its boxes hold the faces). Visits the nodes nearer child first and
/// skips a node whose box lies farther from p than the best face so far (its squared distance
/// beyond the best's by more than 1e-12 of it, so that round-off in a box or a face point never
/// drops a face that ties). Preconditions (InternalError): as NearestMeshPoint's, and a tree of
/// `mesh`'s faces.
MeshPoint NearestMeshPoint(const Eigen::Vector3d& p, const PolygonMesh& mesh, const Bvh& tree);

}  // namespace flexmbs::contact
