#pragma once
// The stiffness of a spur pair's elastic teeth (docs/contact.md, "Spur gears", "Elastic teeth"):
// ISO 6336-1's closed-form single-pair stiffness, and a tooth pair's stiffness at its place on
// the path of contact from two teeth's compliances along their flanks (an FE tooth,
// gear_tooth_fe/) in series with Weber's Hertzian flattening.

#include <optional>
#include <vector>

#include "contact/gears/spur_gear.h"

namespace flexmbs::contact {

/// ISO 6336-1:2019 sec. 9.3 (method B) for a spur pair (beta = 0, z_n = z), all in SI units:
/// the theoretical single-pair stiffness 1 / q' with
///   q' = C1 + C2 / z1 + C3 / z2 + C4 x1 + C5 x1 / z1 + C6 x2 + C7 x2 / z2 + C8 x1^2 + C9 x2^2
/// [mm um / N] (Table 8's coefficients), and the single-pair stiffness
/// c' = c'_th C_M C_R C_B of solid wheels.
struct IsoMeshStiffness {
  double theoretical = 0.0;  ///< c'_th [N/m^2] (1 N/(mm um) = 1e9 N/m^2)
  double c_m = 0.8;          ///< C_M: theory to measurement, 0.8 for solid disks
  double c_r = 1.0;          ///< C_R: wheel blank, 1 for solid disks
  /// C_B = mean over the wheels of [1 + 0.5 (1.2 - h_fP / m)] [1 - 0.02 (20 deg - alpha)]: the
  /// basic rack's dedendum h_fP = h_f* m and pressure angle alpha.
  double c_b = 1.0;
  double single_pair = 0.0;  ///< c' [N/m^2]
};

/// ISO 6336-1's stiffness of the pair of wheels g1 (pinion) and g2 (wheel), valid as the
/// standard states for x1 >= x2 and -0.5 <= x1 + x2 <= 2 (not checked: the value is a fit).
IsoMeshStiffness IsoSinglePairStiffness(const SpurGearSpec& g1, const SpurGearSpec& g2);

/// An isotropic tooth material.
struct ToothMaterial {
  double youngs_modulus = 2.1e11;  ///< E [Pa], steel's
  double poisson_ratio = 0.3;      ///< nu [-]
};

/// Weber's Hertzian flattening of two teeth in line contact (Weber and Banaschek 1953; the form
/// of Cornell 1981, eq. 12): the approach [m] of the two teeth's points at depths h1, h2 [m] below
/// the contact (along the line of action, to the teeth's centre lines) under a load w [N/m] per
/// face width,
///   delta_H = 2 w (1 - nu^2) / (pi E) (ln(2 h1 / a) + ln(2 h2 / a) - nu / (1 - nu)),
/// a = sqrt(8 w R (1 - nu^2) / (pi E)) Hertz's half width, 1/R = 1/rho1 + 1/rho2 from the flanks'
/// radii of curvature rho1, rho2 [m]. All arguments > 0.
double WeberFlattening(double load_per_width, double rho1, double rho2, double h1, double h2,
                       const ToothMaterial& material);

/// One tooth's compliance along its flank: the table an FE tooth gives (gear_tooth_fe/tooth_model.h).
/// Sample k is a load on the flank at roll angle roll[k] (FlankPoint's t, increasing), along the
/// line of action (the flank's normal), per face width.
struct ToothCompliance {
  std::vector<double> roll;  ///< t_k [rad]
  /// q_k [m^2/N]: the tooth's deflection along the line of action where that line crosses the
  /// tooth's centre line, times the face width, per load (bending, shear, rim; the flattening
  /// between the flank and the centre line is WeberFlattening's).
  std::vector<double> compliance;
  std::vector<double> centre_depth;  ///< h_k [m]: from the flank point to the centre line
};

/// InputError (one line) unless `tooth` has two or more samples, as many in each column, finite
/// roll angles > 0 that increase, and compliances and centre depths > 0; `item` names the tooth.
void CheckToothCompliance(const ToothCompliance& tooth, const char* item);

/// The compliance and centre depth of `tooth` at roll angle t [rad], linear between the samples and
/// held beyond them. FLEXMBS_CHECK: at least two samples, increasing roll angles.
struct ToothComplianceAt {
  double compliance = 0.0;    ///< q [m^2/N]
  double centre_depth = 0.0;  ///< h [m]
};
ToothComplianceAt InterpolateCompliance(const ToothCompliance& tooth, double roll);

/// A tooth's coupling to its neighbours through the rim (gear_tooth_fe::ToothCouplingFromFe):
/// for a load per face width on the flank at roll[k], the deflection [m^2/N] per load per face
/// width of the neighbour the same line of action crosses one pitch of roll ahead (roll[k] +
/// 2 pi / z) and behind (roll[k] - 2 pi / z); NaN where that neighbour's point is off its flank.
struct RimCoupling {
  std::vector<double> roll, ahead, behind;
};

/// `values` (a RimCoupling column over `roll`) at roll t, linear between its finite samples and
/// extrapolated past them. FLEXMBS_CHECK: two or more finite samples.
double RimCouplingAt(const std::vector<double>& roll, const std::vector<double>& values, double t);

/// Two elastic teeth in mesh: each wheel's tooth compliance, the material and the load per face
/// width w_ref [N/m] at which the (weakly nonlinear) flattening is linearised.
struct ElasticTeeth {
  ToothCompliance tooth1, tooth2;
  ToothMaterial material;
  double reference_load = 3e5;  ///< w_ref [N/m] (300 N/mm, ISO 6336-1's 100 N/mm and above)
  /// Optional, both or neither: the wheels' coupling through their rims. With them two pairs in
  /// contact on one side share a 2 x 2 compliance (MeshLaw::Forces); tooth1, tooth2 are then the
  /// same segments' own compliances (ToothCouplingFromFe's), not the one-tooth tables.
  std::optional<RimCoupling> rim1, rim2;
  /// true: each pair's flattening at its own load (MeshLaw::Forces solves the series
  /// (q1 + q2) w + delta_H(w) = delta per pair), not linearised at w_ref.
  bool flattening_at_load = false;
};

/// InputError unless E > 0, 0 <= nu < 0.5 and the reference load w_ref > 0 [N/m] (all finite).
void CheckToothMaterial(const ToothMaterial& material, double reference_load);

/// InputError unless the material passes CheckToothMaterial and both tables pass
/// CheckToothCompliance ("gear 1 tooth", "gear 2 tooth").
void CheckElasticTeeth(const ElasticTeeth& teeth);

/// The flanks' flattening compliance [m^2/N] of the tooth pair at roll angles t1, t2 of `pair`:
/// Weber's approach at w_ref over w_ref, delta_H(w_ref, r_b1 t1, r_b2 t2, h1, h2) / w_ref. Roll
/// angles > 0.
double FlatteningCompliance(const ElasticTeeth& teeth, const GearPair& pair, double roll1,
                            double roll2);

/// The single-pair stiffness c(t1, t2) [N/m^2] (per face width) of the tooth pair at roll angles
/// t1, t2 of `pair`: the two teeth's compliances and Weber's flattening at w_ref in series,
///   1 / c = q1(t1) + q2(t2) + delta_H(w_ref, r_b1 t1, r_b2 t2, h1, h2) / w_ref
/// (FlatteningCompliance the last term).
/// Roll angles > 0 (a flank point above the base circle).
double TeethPairStiffness(const ElasticTeeth& teeth, const GearPair& pair, double roll1,
                          double roll2);

}  // namespace flexmbs::contact
