#pragma once
// The Polygonal Contact Model between two markers' surfaces as a force element (docs/contact.md,
// "Polygonal Contact Model"; docs/mbs.md, "Seams for contact"): a rigid-rigid pair, each surface
// a triangle mesh fixed in its marker's frame on an elastic layer.

#include <string>
#include <vector>

#include "contact/geometry/sphere_surface.h"
#include "contact/laws/friction.h"
#include "contact/pcm/foundation.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// One side of a PCM pair: a triangle mesh with vertices in the frame of `marker` (p_MV_M [m],
/// counter-clockwise seen from outside) carried rigidly by the marker, and its elastic layer.
struct PcmSurface {
  std::string name;
  MarkerRef marker;
  contact::PolygonMesh mesh_M;
  contact::ElasticLayer layer;
  bool closed = false;  ///< whether the mesh must be closed (a body's whole boundary)
};

/// Surface A pressing into surface B (B's face normals are the contact normals; take the flatter
/// surface as B). At each evaluation both meshes are placed in W by their markers, the face
/// hierarchies are built (SAH; rebuilt, not refitted, in this first version) with B's faces swept
/// to max_depth, and the elements and their loads follow contact/pcm (ContactElements, SumLoads):
/// A takes the resultant force F and its moment about A's marker origin, B the opposites. Each
/// vertex moves with its marker: v = v_WM + w_WM x (p - p_WM). Potential energy: the layers'
/// contact::ElasticEnergy.
class PcmContactForce final : public ForceElement {
 public:
  /// Checks both surfaces (contact::RequirePcmSurface), the layers, d_A and friction
  /// (contact::MakeElasticFoundation) and max_depth > 0 [m]; InputError "force element '<name>':
  /// <what>" otherwise.
  PcmContactForce(std::string name, PcmSurface A, PcmSurface B, double areal_damping,
                  const contact::RegularisedCoulomb& friction, double max_depth);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// Per element, sum_ij s_i s_j J_i^T K J'_j over the two bodies (s_A = 1, s_B = -1; J the
  /// jacobian of the body's material point at the pressure centre, J' at the point whose velocity
  /// enters: A's point under the pressure centre, B's at it) with K the element's
  /// d_displacement (dh/dx) and d_velocity (dh/du) (contact::ElementLoad). Exact in u; in x with
  /// the patches' areas and pressure centres held and without the levers' rotation (the load
  /// times the rotation, as the other contact elements).
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;
  bool is_contact() const override { return true; }
  /// One load per element carrying load: at A's point under the pressure centre, B's normal, the
  /// element's force on A.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;

 private:
  /// Both meshes placed in W, with their vertices' velocities, and the elements between them.
  struct Evaluation;
  Evaluation Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const;
  /// Each element's load, and A's point under its pressure centre [m].
  struct ElementState {
    contact::ElementLoad load;
    Eigen::Vector3d p_WA_W;
  };
  ElementState StateOf(const Evaluation& e, const contact::PcmElement& element) const;

  std::string name_;
  PcmSurface A_, B_;
  contact::ElasticFoundation law_;
  double max_depth_;
};

}  // namespace flexmbs::mbs
