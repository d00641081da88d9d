#pragma once
// The mesh force of a spur pair with compliant teeth on rigid flanks (docs/contact.md, "Spur
// gears"): each tooth pair in contact a linear spring-dashpot along its line of action, of the
// single-pair mesh stiffness of ISO 6336-1 or of elastic teeth in series at the pair's place on the
// path of contact, and the torques on both wheels. Axes at rest.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/tooth_stiffness.h"
#include "contact/laws/normal_law.h"

namespace flexmbs::contact {

/// The compliance of a mesh.
struct GearMeshCompliance {
  /// c' [N/m per m of face width]: the single-pair stiffness, force per face width along the line
  /// of action per deflection; ISO 6336-1:2019 sec. 9's 14 N/(mm um) = 1.4e10 N/m^2 for steel
  /// spur pairs of the basic rack profile.
  double single_pair_stiffness = 1.4e10;
  double damping = 0.0;  ///< c [N s/m] per tooth pair in contact, on the deflection's rate
};

/// The normal law of one tooth pair: F = max(0, c' b delta + c delta') (LinearLaw) with b the
/// common face width min(b1, b2) [m]. InputError "mesh stiffness c' [N/m^2] <value> must be finite
/// and > 0" or LinearLaw's for a negative damping.
NormalLaw ToothPairLaw(const GearMeshCompliance& compliance, const GearPair& pair);

/// How far a load F on a tooth pair moves its teeth along the line of action [m] (each tooth's
/// tangential deflection, tooth_stiffness.h's q F / b, and the two flanks' flattening); zero for
/// rigid teeth. With an undamped law they add up to the pair's penetration.
struct ToothPairDeflection {
  double tooth1 = 0.0, tooth2 = 0.0, flattening = 0.0;
};

/// The forces of MeshLaw::Forces with their exact derivatives by the pairs' penetrations and
/// rates (each pair's roll angles, and so its tables' values, held), and the springs' energy.
struct MeshPairForces {
  std::vector<double> force;  ///< F_i [N], in the order of the pairs
  Eigen::MatrixXd d_delta;    ///< K_ij = dF_i / d delta_j [N/m]
  Eigen::MatrixXd d_rate;     ///< D_ij = dF_i / d delta'_j [N s/m]
  /// [J]: sum of the elastic forces F_e,i times delta_i / 2 (the potential 1/2 delta' C^-1 delta
  /// for a symmetric C); at each pair's load, the integral (F_e delta - b s w^2) / 2 of F_e over
  /// delta, s = (1 - nu^2) / (pi E).
  double energy = 0.0;
};

/// The tooth pairs' laws of a mesh: one law for every pair (teeth of constant stiffness, the rigid
/// flanks' model), or, for massless elastic teeth, a LinearLaw(c(t1, t2) b, c) per pair from its
/// roll angles (TeethPairStiffness: both teeth and the flattening as springs in series, b the
/// common face width). The series is solved quasi-statically (docs/contact.md, "Elastic teeth"):
/// exact for massless teeth when the damping c acts on the pair's whole deflection.
class MeshLaw {
 public:
  /// Every tooth pair takes `law` (implicit: a NormalLaw is the constant-stiffness mesh).
  MeshLaw(NormalLaw law);  // NOLINT(google-explicit-constructor)
  /// Elastic teeth of `pair` with a damping c >= 0 [N s/m] per tooth pair in contact.
  /// InputError from CheckElasticTeeth, or LinearLaw's for a negative damping, for one wheel's
  /// rim coupling without the other's, for a rim column that is not a table over increasing roll
  /// angles with two or more finite values in [0, q(t)) (the neighbour moves less than the loaded
  /// tooth).
  MeshLaw(const GearPair& pair, ElasticTeeth teeth, double damping);
  /// The law of tooth pair `tp`.
  NormalLaw PairLaw(const ToothPair& tp) const;
  /// The forces [N] of `pairs` in contact (penetrations -g > 0) at the penetrations' rates
  /// `rates` [m/s]: each its PairLaw's, or, for elastic teeth with both rims' coupling and two
  /// pairs on one side, together: delta = C F_e with C_ii = 1 / (c(t1, t2) b) and, pair A the one
  /// nearer wheel 1's tip, C_AB = (rim1 ahead(t1_B) + rim2 behind(t2_B)) / b (A's teeth under B's
  /// load), C_BA = (rim1 behind(t1_A) + rim2 ahead(t2_A)) / b; a pair whose F_e would pull is
  /// dropped (the other takes delta / C_jj); F = max(0, F_e + c delta'). With
  /// ElasticTeeth::flattening_at_load, each pair's F_e = b w with w the load per face width that
  /// solves (q1 + q2) w + delta_H(w) = delta (WeberFlattening at w: delta_H ~ w ln(1/w); bisection
  /// to 1e-15 of w's bracket [0, delta / (q1 + q2)]); coupled as well, the two pairs' loads solve
  /// (q1 + q2)_i w_i + delta_H,i(w_i) + b C_ij w_j = delta_i together (Newton's method from the
  /// linearised solution, to 1e-15 of w; a pair whose w would fall to 0 or below dropped, the
  /// other at its load alone).
  std::vector<double> Forces(const std::vector<ToothPair>& pairs,
                             const std::vector<double>& rates) const;
  /// Forces (the same numbers) with their derivatives: PairLaw's d_delta, d_rate on the diagonal;
  /// coupled, K = C^-1 on the pairs kept (the dropped pair's row zero, the other's 1 / C_jj); at
  /// each pair's load, dF_e / d delta = b / (q1 + q2 + delta_H(w) / w - 2 s) (implicit
  /// differentiation of the series; d delta_H / dw = delta_H / w - 2 s,
  /// s = (1 - nu^2) / (pi E)), coupled too K = b J^-1 with J the Newton matrix at the solution;
  /// D = c on the diagonal; a row zero where F clips at 0.
  MeshPairForces ForcesWithDerivatives(const std::vector<ToothPair>& pairs,
                                       const std::vector<double>& rates) const;
  /// Whether the pairs in contact are coupled through the rims (Forces).
  bool coupled() const { return teeth_ && teeth_->rim1 && teeth_->rim2; }
  /// Whether Forces differs from the pairs' PairLaw (coupled, or the flattening at each pair's
  /// load): the force element then takes the mesh's forces and their cross terms together
  /// (ForcesWithDerivatives) instead of one compliant contact per pair.
  bool joint() const { return coupled() || (teeth_ && teeth_->flattening_at_load); }
  /// The deflections under a load F [N] on `tp` alone (Deflections of the one pair).
  ToothPairDeflection Deflection(const ToothPair& tp, double force) const;
  /// The deflections of `pairs` under their loads `forces` [N] (elastic teeth; zeros otherwise):
  /// each tooth q(t) w (w = F / b) and, coupled through the rims with two pairs on one side, the
  /// neighbour's share of the other pair's load (pair A's teeth rim1 ahead(t1_B) w_B and rim2
  /// behind(t2_B) w_B, B's rim1 behind(t1_A) w_A and rim2 ahead(t2_A) w_A); the flattening
  /// delta_H(w) at the pair's load (ElasticTeeth::flattening_at_load) or linearised at w_ref,
  /// delta_H(w_ref) w / w_ref. Under Forces' undamped loads they add up to each pair's
  /// penetration.
  std::vector<ToothPairDeflection> Deflections(const std::vector<ToothPair>& pairs,
                                               const std::vector<double>& forces) const;
  bool elastic() const { return teeth_.has_value(); }
  /// The elastic teeth (their tables and material); nullptr for teeth of constant stiffness.
  const ElasticTeeth* teeth() const { return teeth_ ? &*teeth_ : nullptr; }

 private:
  /// t_i held at or above the first roll angle of the tooth's table (the form circle).
  std::pair<double, double> Rolls(const ToothPair& tp) const;
  /// Pair `tp`'s teeth and flattening in series per face width: the approach at a load w [N/m]
  /// and its slope (gear_mesh_force.cc).
  struct Series;
  Series PairSeries(const ToothPair& tp) const;
  /// The elastic force [N] of pair `tp` at penetration delta > 0 with its flattening at its load,
  /// its derivative by delta [N/m] and its energy [J] (MeshPairForces).
  struct AtLoad {
    double force = 0.0, d_delta = 0.0, energy = 0.0;
  };
  AtLoad ForceAtLoad(const ToothPair& tp, double delta) const;
  /// The coupled forces of two pairs on one side (Forces) into `out`.
  void CoupledForces(const std::vector<ToothPair>& pairs, const std::vector<double>& rates,
                     MeshPairForces* out) const;
  /// The coupled pairs' elastic forces with the flattening at each pair's load, from the
  /// linearised `elastic` forces of compliance C at penetrations delta (both kept), with their
  /// K: -1, or the pair whose load fell to 0 or below (the caller drops it; both left as given).
  Eigen::Index CoupledAtLoad(const std::vector<ToothPair>& pairs, const Eigen::Matrix2d& C,
                             const Eigen::Vector2d& delta, Eigen::Vector2d* elastic,
                             Eigen::Matrix2d* K) const;

  NormalLaw law_;
  std::optional<ElasticTeeth> teeth_;
  GearPair pair_;  ///< the elastic teeth's pair (their base radii)
  double face_width_ = 0.0, damping_ = 0.0;
};

/// One tooth pair's load: F >= 0 [N] pushes wheel 2 along n_12 at the contact point and wheel 1
/// the opposite way.
struct ToothPairLoad {
  ToothPair pair;
  double force = 0.0;
};

/// The loads of a mesh: every pair in contact and the torques about +z [N m] on both wheels.
struct MeshLoads {
  std::vector<ToothPairLoad> pairs;
  /// sum of p_O1C x (-F n_12): -sigma F r_b1 per pair on the line of action
  double torque1 = 0.0;
  /// sum of (p_O1C - O2) x (F n_12): -sigma F r_b2 per pair on the line of action
  double torque2 = 0.0;
};

/// The mesh loads of `pair` at centre distance a [m] (axes at rest), angles phi1, phi2 [rad] and
/// angular velocities omega1, omega2 [rad/s] about +z: each tooth pair of MeshingToothPairs with
/// a penetration delta = -g > 0 carries its law(delta, delta'), delta' = -n_12 . (v2 - v1) the
/// gap's rate at the contact point (sigma (r_b1 omega1 + r_b2 omega2) on the line of action,
/// dg/dphi_i = -sigma r_bi; a corner's lever about the wheel whose corner it is is shorter).
MeshLoads EvaluateMesh(const GearPair& pair, const MeshLaw& law, double centre_distance,
                       double phi1, double phi2, double omega1, double omega2);

/// The static transmission error [m] of `pair` at wheel 1's angle phi1 [rad] and centre distance
/// a [m] under a torque T > 0 [N m] driving wheel 1 about +z against wheel 2: how far wheel 2
/// lags its rigid kinematic position along the line of action, delta = r_b2 (phi2 - phi2_0)
/// (phi2_0 = TouchingAngle2 on the positive flanks), where the mesh's torque on wheel 1 balances
/// T. Found by bisection on delta (the mesh torque grows with it). With rigid flanks every pair
/// in contact takes delta, so this is T / (r_b1 b sum_pairs c) (T / (r_b1 c' b n) for n pairs of
/// constant stiffness).
double StaticTransmissionError(const GearPair& pair, const MeshLaw& law, double centre_distance,
                               double phi1, double torque);

}  // namespace flexmbs::contact
