#pragma once
// The narrow phase of the Polygonal Contact Model (docs/contact.md, "Polygonal Contact Model"):
// the contact element of a triangle of surface A penetrating a triangle of surface B, and the
// elements of two meshes from their candidate pairs.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "contact/geometry/sphere_surface.h"
#include "contact/pcm/candidate_pairs.h"

namespace flexmbs::contact {

/// The patch where triangle face_A of A lies under triangle face_B of B: the part of A's
/// triangle projected along B's normal onto B's plane, within B's triangle and at depths
/// 0 <= delta <= max_depth under it. The depth delta(x) (how far A's triangle lies under B's
/// plane at x, along n) is linear over the patch; the force of a foundation p = c delta acts at
/// the pressure centre.
struct PcmElement {
  int face_A = 0;
  int face_B = 0;
  double area = 0.0;    ///< of the patch in B's plane [m^2]
  double volume = 0.0;  ///< integral of delta over the patch [m^3]
  double depth = 0.0;   ///< volume / area: delta at the barycentre [m]
  double depth_squared = 0.0;  ///< integral of delta^2 over the patch [m^4] (the foundation's energy)
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();           ///< B's outward unit normal: pushes A out
  Eigen::Vector3d barycentre_W = Eigen::Vector3d::Zero();       ///< of the patch, in B's plane [m]
  Eigen::Vector3d pressure_centre_W = Eigen::Vector3d::Zero();  ///< integral(delta x) / volume, in B's plane [m]
  /// Barycentric weights of the pressure centre on B's triangle and of the point of A's triangle
  /// under it (pressure_centre_W - delta normal_W), vertex by vertex of each face: they carry the
  /// vertices' velocities (a deforming surface's too) to the element.
  Eigen::Vector3d weights_A = Eigen::Vector3d::Zero();
  Eigen::Vector3d weights_B = Eigen::Vector3d::Zero();
  /// The gradients of those weights along B's plane: row k is the gradient of vertex k's weight as
  /// the point moves in the plane, in W [1/m] (the weights are linear over the patch).
  Eigen::Matrix3d weight_gradients_A = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d weight_gradients_B = Eigen::Matrix3d::Zero();
  /// The patch's first and second moments of area about the pressure centre, in W: integral of
  /// (x - x_p) dA [m^3] and of (x - x_p)(x - x_p)^T dA [m^4]. With them the integral of a product
  /// of linear functions over the patch follows from their values and gradients at x_p (the
  /// consistent Jacobian of a lumped load, mbs/pcm_contact_force.h).
  Eigen::Vector3d first_moment_W = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment_W = Eigen::Matrix3d::Zero();
};

/// The element of triangle (a0, a1, a2) of A under triangle (b0, b1, b2) of B (both
/// counter-clockwise seen from outside their bodies), or none: no overlap, zero volume, or
/// normals that do not oppose (n_A . n_B >= 0: A's triangle faces away from B). Faces are left
/// 0 for the caller. Preconditions (InternalError): max_depth > 0.
std::optional<PcmElement> TriangleElement(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                                          const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                                          double max_depth);

/// The elements of the candidate `pairs` (faces of A, faces of B) of two triangle meshes
/// (RequirePcmSurface), recomputed from the current vertices. B's hierarchy must be swept to a depth
/// >= max_depth [m] for the pairs to hold every element.
std::vector<PcmElement> ContactElements(const PolygonMesh& A, const PolygonMesh& B, const std::vector<FacePair>& pairs,
                                        double max_depth);

}  // namespace flexmbs::contact
