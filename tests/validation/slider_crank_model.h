#pragma once
// The flexible slider-crank of Simo & Vu-Quoc ("On the dynamics of flexible beams under large
// overall motions - the plane case, Part II", J. Appl. Mech. 53, 1986), shared by
// tests/validation/slider_crank_test.cc and bench/slider_crank_bench.cc.
//
// A rigid crank of r = 0.15 m turns about W z by a prescribed angle that spins it up smoothly
// to 150 rad/s in T = 0.15 s (mbs::MakeSpinUp, Kane et al.'s spin-up profile); a steel
// connecting rod of L = 0.3 m and 6 mm diameter is pinned (revolute joints) to the crank's tip
// and to a slider on a prismatic joint along W x; no gravity. All three joints have parallel
// axes, so the loop is planar in 3-D and 3 of its rows are dropped as redundant
// (constraint_redundancy.h). The crank, rod and slider dimensions and the crank speed are the
// benchmark's as stated in the task; E = 200 GPa, rho = 7870 kg/m^3 and the slider mass
// 0.033 kg are not checked against the paper (the published text was not reachable here): the
// reference (slider_crank_reference.py) uses the same numbers, so the comparison with it does
// not depend on them.
//
// The rod: tests/validation/flexible_pendulum_model.h's BuildLink (a hex20 bar of steel,
// E = 210 GPa, rho = 7850 kg/m^3, clamped at its root face, every clamped eigenmode), with a
// section of thickness h (in the plane, B y) and width b (B z) chosen so that its E I about z and
// rho A are those of the round rod of the benchmark's material:
//   b h^3 / 12 E_steel = E pi d^4 / 64,   b h rho_steel = rho pi d^2 / 4
// (h = 5.07 mm, b = 5.60 mm: the out-of-plane modes 10 % above the in-plane ones). Its root face
// is held by the body frame, which the crank's revolute joint pins: a fixed-interface basis; the
// modes kept are the lowest in-plane ones (even under the reflection z -> -z: bending in B y and
// axial), and the SID body gets the averaging markers "tip" and "mid" (the section at L / 2).

#include <Eigen/Core>
#include <vector>

#include "mbs/ode_integrator.h"
#include "mbs/time_function.h"
#include "sid/reduced_body.h"
#include "tests/validation/flexible_pendulum_model.h"

namespace flexmbs::validation {

/// The benchmark's numbers (see the file comment for their sources).
struct SliderCrankData {
  double crank = 0.15;           ///< r [m]
  double rod_length = 0.3;       ///< L [m]
  double rod_diameter = 6e-3;    ///< d [m]
  double youngs_modulus = 2e11;  ///< E [Pa]
  double density = 7870.0;       ///< rho [kg/m^3]
  double slider_mass = 0.033;    ///< [kg]
  double spin = 150.0;           ///< the crank's final angular velocity [rad/s]
  double ramp_time = 0.15;       ///< T [s]
};

/// The meshed rod (cells along x, y, z; an even number along x for the "mid" section) and the
/// columns of its complete clamped basis that are in-plane modes, ascending in frequency.
struct SliderCrankRod {
  FeLink link;
  std::vector<Eigen::Index> in_plane_modes;
};
SliderCrankRod BuildRod(const SliderCrankData& data, const Eigen::Vector3i& cells = Eigen::Vector3i(12, 1, 1));

/// The SID body "rod" of the lowest `modes` in-plane modes (markers "tip" and "mid"), with the
/// geometric stiffening blocks when `stiffening`.
sid::ReducedBody RodBody(const SliderCrankRod& rod, Eigen::Index modes, bool stiffening);

/// How a run is integrated and recorded.
struct CrankRunOptions {
  bool stiffening = true;         ///< the rod's geometric stiffening in the equations of motion
  bool planar = false;            ///< run as a planar scene (mbs/planar.h: in-plane columns only)
  double end_time = 0.4;          ///< [s]
  double output_interval = 5e-4;  ///< [s]
  mbs::OdeOptions integrator;
};

/// A run's history at the output times.
struct CrankRun {
  std::vector<double> time;  ///< [s]
  /// The distance of the rod's midpoint ("mid") from the chord through its ends (the body
  /// frame's origin and "tip"), positive along z_W x chord [m].
  std::vector<double> mid_deflection;
  long dropped_rows = 0;  ///< constraint rows dropped as redundant
  long kept_velocities = 0, kept_rows = 0;  ///< the solves' velocity columns and constraint rows
  long steps = 0, rhs_evaluations = 0;
  double cpu_seconds = 0.0;  ///< process CPU time of the integration
};

/// Runs the slider-crank with the rod `rod_body` from rest at theta = 0 (crank, rod and slider
/// on W x, undeformed).
CrankRun RunSliderCrank(const SliderCrankData& data, const sid::ReducedBody& rod_body, const CrankRunOptions& options);

/// max_k |a_k - b_k| over k with times[k] in [from, to].
double LargestDifference(const std::vector<double>& times, const std::vector<double>& a, const std::vector<double>& b,
                         double from, double to);

}  // namespace flexmbs::validation
