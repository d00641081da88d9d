#pragma once
// The elastic-foundation law of the Polygonal Contact Model (docs/contact.md, "Polygonal Contact
// Model"): pressure from the depth through two elastic layers in series, areal damping and
// regularised Coulomb friction; the load of each element and of a pair.

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "contact/geometry/sphere_surface.h"
#include "contact/laws/friction.h"
#include "contact/pcm/contact_element.h"

namespace flexmbs::contact {

/// A surface's elastic layer (Winkler foundation): modulus E [Pa] over thickness h [m], a
/// spring of E / h per unit area [N/m^3].
struct ElasticLayer {
  double modulus = 0.0;    ///< E [Pa] (for a thin, laterally confined layer its constrained modulus)
  double thickness = 0.0;  ///< h [m]
};

/// The law of a PCM pair: p = c delta + d_A ddelta/dt, clipped at 0, with friction.
struct ElasticFoundation {
  double stiffness = 0.0;      ///< c [N/m^3] = 1 / (h_A / E_A + h_B / E_B): two layers in series
  double areal_damping = 0.0;  ///< d_A [N s/m^3]
  RegularisedCoulomb friction;
};

/// The law of surfaces with layers A and B: E and h finite and > 0, d_A finite and >= 0;
/// InputError "layer <modulus|thickness> of surface '<name>' <value> must be finite and > 0"
/// otherwise (the caller adds the file and item).
ElasticFoundation MakeElasticFoundation(const ElasticLayer& A, std::string_view name_A, const ElasticLayer& B,
                                        std::string_view name_B, double areal_damping, const RegularisedCoulomb& friction);

/// The energy stored in the layers by the elements [J]: c/2 times the sum of their integrals of
/// delta^2, whose derivative by a rigid approach along a flat B's normal is c V, the force.
double ElasticEnergy(const ElasticFoundation& law, const std::vector<PcmElement>& elements);

/// An element's load on A (B takes its opposite at the same point).
struct ElementLoad {
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();  ///< normal and friction force on A [N]
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();  ///< where it acts: the pressure centre [m]
  double normal_force = 0.0;                          ///< F_N >= 0 [N]
  /// dF/dv [N s/m] by the relative velocity v = v_A - v_B: -(n + dF_T/dF_N) d_A A n^T +
  /// dF_T/dv_T (I - n n^T); 0 where F_N is clipped.
  Eigen::Matrix3d d_velocity = Eigen::Matrix3d::Zero();
  /// dF/du [N/m] by a displacement u of A against B at the pressure centre, the patch's area
  /// held: -(n + dF_T/dF_N) c A n^T (dV = -A n . u; exact for the sum over a flat B's elements
  /// without damping; the damping's d_A v_N dA/du is left out); 0 where F_N is clipped.
  Eigen::Matrix3d d_displacement = Eigen::Matrix3d::Zero();
  /// dF/dF_N = n + dF_T/dF_N [1]: how the force turns with the normal force; 0 where F_N is clipped.
  Eigen::Vector3d d_normal_force = Eigen::Vector3d::Zero();
};

/// The element's load at relative velocity v = v_A - v_B [m/s] of A's point against B's at the
/// pressure centre: F_N = max(0, c V - d_A A n . v) (the depth grows at -n . v), F = F_N n +
/// F_T(v - n n . v, F_N) (contact/laws/friction.h). The pressure c delta, linear over the patch,
/// integrates to c V at the pressure centre; damping and friction act there too. With the
/// derivatives the implicit method needs.
ElementLoad Evaluate(const ElasticFoundation& law, const PcmElement& element, const Eigen::Vector3d& v_AB_W);

/// The resultant on A of a pair's elements: force and moment about a point (B takes their
/// opposites about the same point), and the total normal force.
struct PairLoad {
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   ///< [N]
  Eigen::Vector3d moment_W = Eigen::Vector3d::Zero();  ///< about the given point [N m]
  double normal_force = 0.0;                           ///< sum of F_N [N]
};

/// The velocity of A's point under the element's pressure centre against B's there,
/// v_A - v_B [m/s], from the vertex velocities of A and B (3 x V each) through the faces' weights.
Eigen::Vector3d RelativeVelocity(const PcmElement& element, const PolygonMesh& A,
                                 const Eigen::Matrix3Xd& vertex_velocities_A_W, const PolygonMesh& B,
                                 const Eigen::Matrix3Xd& vertex_velocities_B_W);

/// Sums the elements' loads on A about p_W; each element's relative velocity from the vertex
/// velocities of A and B (3 x V each [m/s], rigid or deformed) through its faces' weights.
PairLoad SumLoads(const ElasticFoundation& law, const std::vector<PcmElement>& elements, const PolygonMesh& A,
                  const Eigen::Matrix3Xd& vertex_velocities_A_W, const PolygonMesh& B,
                  const Eigen::Matrix3Xd& vertex_velocities_B_W, const Eigen::Vector3d& p_W);

}  // namespace flexmbs::contact
