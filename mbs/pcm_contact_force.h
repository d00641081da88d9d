#pragma once
// The Polygonal Contact Model between two markers' surfaces as a force element (docs/contact.md,
// "Polygonal Contact Model"; docs/mbs.md, "Seams for contact"): two surfaces on elastic layers,
// each a rigid triangle mesh on a marker or a reduced body's contact surface deformed by its modes
// (mbs/pcm_surface.h).

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "contact/laws/friction.h"
#include "contact/pcm/candidate_pairs.h"
#include "contact/pcm/foundation.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"
#include "mbs/pcm_surface.h"

namespace flexmbs::mbs {

/// How the element keeps its face hierarchies between evaluations: refitted to the moved
/// (deformed) meshes and rebuilt only past contact::Bvh::Degradation() kRebuildDegradation, or
/// rebuilt at every evaluation (for comparison: bench/pcm_bench.cc).
enum class PcmTreeUpdate { kRefit, kRebuild };

/// Surface A pressing into surface B (B's face normals are the contact normals; take the flatter
/// surface as B). At each evaluation both meshes are placed in W (a modal side deformed by its
/// modes), the face hierarchies (SAH, B's faces swept to max_depth) refitted to them, and the
/// elements and their loads follow contact/pcm (ContactElements, Evaluate): A takes each element's
/// force F at the pressure centre, B the opposite. On the rigid coordinates A's frame takes the
/// resultant and its moment about A's marker origin, B the opposites; on a modal side the modes
/// take (R sum_k w_k phi_k)^T F of each element, w the barycentric weights of the element's
/// material point on the face (A's point under the pressure centre on A, the pressure centre on
/// B). Each vertex moves with its marker and, on a modal side, its modes (PlacedPcmSurface), so
/// the relative velocity at the pressure centre includes the elastic velocities. Potential
/// energy: the layers' contact::ElasticEnergy.
///
/// The hierarchies are a cache (docs/mbs.md, "Seams for contact"): the one mutable state of the
/// element, guarded by a mutex (an evaluation that finds it taken builds its own trees). The
/// candidate pairs, hence every load, are the same from a refitted tree as from a new one.
class PcmContactForce final : public ForceElement {
 public:
  /// Past this Degradation() of a refitted tree it is rebuilt (bench/pcm_bench.cc: queries 1.6x
  /// slower at 1.35, none at 1.04).
  static constexpr double kRebuildDegradation = 1.3;

  /// Checks both surfaces (contact::RequirePcmSurface), the layers, d_A and friction
  /// (contact::MakeElasticFoundation) and max_depth > 0 [m]; InputError "force element '<name>':
  /// <what>" otherwise.
  PcmContactForce(std::string name, PcmSurface A, PcmSurface B, double areal_damping,
                  const contact::RegularisedCoulomb& friction, double max_depth,
                  PcmTreeUpdate tree_update = PcmTreeUpdate::kRefit);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// Per element and pair of sides i, j (s_A = 1, s_B = -1): dh/du += s_i s_j J_i^T (dF/dv) J'_j
  /// (J_i side i's material point at the pressure centre, with its modal columns R sum_k w_k
  /// phi_k; J'_j side j's point whose velocity enters: A's point under the pressure centre, B's
  /// at it), exact; dh/dx the lumped load's consistent derivative s_i s_j c integral(J_i(x)^T d_F
  /// n^T J'_j(x) dA) over the patch (d_F = dF/dF_N; J linear over the patch through the weights'
  /// gradients; the patch's moments about the pressure centre: the force's change and the
  /// pressure centre's shift), with the normals, the areas' change by in-plane motion, the
  /// damping's area and the levers' and mode shapes' rotation held (of order depth / element size;
  /// docs/contact.md).
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;
  bool is_contact() const override { return true; }
  /// One load per element carrying load: at A's point under the pressure centre, B's normal, the
  /// element's force on A.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// How many times the element has built a hierarchy (both sides counted) since construction.
  int tree_builds() const;
  /// The pressing surface and the one pressed (its normals the contact normals).
  const PcmSurface& A() const { return A_; }
  const PcmSurface& B() const { return B_; }

 private:
  /// Both sides placed at y and the elements between them.
  struct Evaluation;
  Evaluation Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const;
  /// The candidate pairs of the placed meshes, from the cached trees refitted (or rebuilt).
  std::vector<contact::FacePair> CandidatePairs(const contact::PolygonMesh& A, const contact::PolygonMesh& B) const;
  /// Each element's load, and A's point under its pressure centre [m].
  struct ElementState {
    contact::ElementLoad load;
    Eigen::Vector3d p_WA_W;
  };
  ElementState StateOf(const Evaluation& e, const contact::PcmElement& element) const;

  /// The hierarchies kept between evaluations, and how often they were built.
  struct TreeCache {
    std::mutex mutex;
    std::optional<contact::Bvh> A, B;
    int builds = 0;
  };

  std::string name_;
  PcmSurface A_, B_;
  contact::ElasticFoundation law_;
  double max_depth_;
  PcmTreeUpdate tree_update_;
  std::unique_ptr<TreeCache> trees_;
};

}  // namespace flexmbs::mbs
