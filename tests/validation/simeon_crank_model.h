#pragma once
// B. Simeon's flexible slider crank, the IVP Test Set problem "crank" (Simeon, "Modelling a
// flexible slider crank mechanism by a mixed system of DAEs and PDEs", Math. Modelling of
// Systems 2, 1996; the Test Set's crank.f and cranki.f, its initial values INIT and reference
// solution SOLN at t = 0.1 s), for tests/validation/simeon_crank_test.cc.
//
// The mechanism (crank.f, default ipar = (0, 0): linear stiffness, no damping, no gravity): a
// rigid crank of L1 = 0.15 m turned about W z by phi1 = 150 t; a steel rod of L2 = 0.3 m with a
// square 8 x 8 mm section pinned at the crank's tip A; at its other end B a slider (half the rod's
// mass) on W x. Simeon's coordinates: phi1, the rod angle phi2, the slider position x3 and four
// modal coordinates q of the rod in a floating frame with origin A and x along the rod.
//
// The rod here: a sid::ReducedBody built from crank.f's discretisation, body frame B = Simeon's
// rod frame (Bo at A, x along the rod, y = z x x in the plane, z = W z). A material point of
// the centreline x = L2 xi moves by u = Phi(xi) q with, per mode (crank.f's order),
//
//   q1, q2: (0, sin(pi xi), 0), (0, sin(2 pi xi), 0)   lateral, vanishing at both ends
//   q3, q4: (4 xi (1 - xi), 0, 0), (xi (2 xi - 1), 0, 0)  axial, quadratic: q3 the midpoint's,
//                                                          q4 B's axial displacement,
//
// of a slender rod (dm = rho A dx; the section is rigid and enters only the rigid inertia J0,
// as in crank.f's J2 = M2 (L2^2 / 3 + H^2 / 12)). So B stays on the frame's x axis at
// (L2 + q4, 0, 0): Simeon's constraints are the revolute joints at A and B and the slider's
// prismatic joint. Every SID block is a linear function of the rod's mass integrals
// (RodIntegrals: first moments, x-weighted moments and the products int Phi_i Phi_j^T dm), which
// crank.f gives in closed form. Two of crank.f's numbers are not those integrals, and the model
// keeps them, so that it is the published discrete model: crank.f evaluates pi as 3.1415927
// (SimeonCrankData::pi), and its axial mass block MQ(3:4, 3:4) = rho A L2 [8 1; 1 2] is 15 times
// int N_i N_j dm (SimeonCrankData::axial_mass_scale), while its first moments and its coupling
// matrix BQ are the consistent integrals. In the SID blocks that a motion in the plane reaches,
// the axial shapes' products with themselves (crank.f's MQ block) appear only as
// int Phi_j . Phi_k dm (Me, the z z entries of J's order 2 and Gr's order 1, the w_z^2 column
// of Oe's order 1) and the axial-lateral products (crank.f's BQ) only as (int Phi_j x Phi_k dm)_z
// (Cr's order 1, Ge), so crank.f's model is a SID body exactly: its equations are Lagrange's
// equations of the floating-frame kinetic energy with these integrals (checked by
// tests/validation/simeon_crank_reference.py).

#include <Eigen/Core>
#include <array>

#include "mbs/ode_integrator.h"
#include "sid/reduced_body.h"

namespace flexmbs::validation {

/// crank.f's data (its names in brackets), SI units.
struct SimeonCrankData {
  double crank_length = 0.15;         ///< L1 [m]
  double crank_mass = 0.36;           ///< M1 [kg]
  double crank_inertia = 0.002727;    ///< J1 [kg m^2], about the crank's pivot
  double rod_length = 0.30;           ///< L2 [m]
  double rod_mass = 0.151104;         ///< M2 = RHO BB HH L2 [kg]
  double rod_inertia = 0.0045339259;  ///< J2 [kg m^2] about A: M2 (L2^2 / 3 + HH^2 / 12), rounded
  double slider_mass = 0.075552;      ///< M3 [kg]
  double youngs_modulus = 0.2e12;     ///< EE [Pa]
  double width = 0.008;               ///< BB [m], the section across the plane (B z)
  double height = 0.008;    ///< HH [m], the section in the plane (B y): EI = EE BB HH^3 / 12
  double density = 7870.0;  ///< RHO [kg/m^3]
  double spin = 150.0;      ///< OMEGA [rad/s]: phi1 = OMEGA t
  double pi = 3.1415927;    ///< crank.f's PI, in its closed forms
  /// crank.f's axial mass block over the consistent one (15); 1 gives the consistent rod.
  double axial_mass_scale = 15.0;
};

/// The rod's modes, in crank.f's order.
inline constexpr int kRodModes = 4;

/// Simeon's state as cranki.f orders it: phi1, phi2, x3, q1..q4 [rad, rad, m, m]; their rates;
/// their accelerations; the multipliers lambda1 (the rod end's constraint across W x, whose
/// force on B is -lambda1 along W y), lambda2 (the slider at B: -lambda2 is the rod's force on
/// the slider along W x), lambda3 (phi1 = OMEGA t: -lambda3 is the driving torque) [N, N, N m].
using SimeonState = Eigen::Matrix<double, 24, 1>;

/// cranki.f's INIT: "close to smooth motion", accelerations and multipliers consistent for
/// ipar = (0, 0), each rounded to 9 (positions, velocities) or 16 digits.
SimeonState SimeonInitialValues();

/// The rod's mass and stiffness integrals over its centreline (slender rod, dm = rho A dx,
/// r = (x, 0, 0)): all a SID body of these modes needs (RodBody).
struct RodIntegrals {
  double mass = 0.0;    ///< m [kg]
  double length = 0.0;  ///< L [m]
  Eigen::Matrix3d inertia_Bo =
      Eigen::Matrix3d::Zero();                      ///< int r~ r~^T dm with the section [kg m^2]
  std::array<Eigen::Vector3d, kRodModes> first{};   ///< int Phi_i dm [kg m/q]
  std::array<Eigen::Vector3d, kRodModes> moment{};  ///< int x Phi_i dm [kg m^2/q]
  /// int Phi_i Phi_j^T dm at i n + j [kg m^2/q^2].
  std::array<Eigen::Matrix3d, kRodModes * kRodModes> product{};
  Eigen::Matrix4d stiffness =
      Eigen::Matrix4d::Zero();  ///< int (EI v_i'' v_j'' + EA u_i' u_j') dx [N m/q^2]
};

/// crank.f's closed forms, with data.pi and data.axial_mass_scale (file comment).
RodIntegrals CrankRodIntegrals(const SimeonCrankData& data);

/// The integrals by `points`-point Gauss-Legendre quadrature of the shapes (true pi, consistent
/// axial mass): what CrankRodIntegrals must give with data.pi = pi and axial_mass_scale = 1.
RodIntegrals QuadratureRodIntegrals(const SimeonCrankData& data, int points);

/// Per mode j at xi = x / L in [0, 1]: the displacement Phi_j(xi) [m/q] (columns).
Eigen::Matrix<double, 3, kRodModes> RodShapes(double xi);

/// The SID body "rod" (docs/sid.md) of `integrals`: order-1 mdCM, Ct (order 0), Cr, Gr, Oe;
/// order-2 J; Me, Ge, Ke; no damping, no stiffening; nodes "root" (A, Bo) and "tip" (B), whose
/// rotation psi is the lateral modes' slope about B z (with data.pi).
sid::ReducedBody RodBody(const RodIntegrals& integrals, const SimeonCrankData& data);

/// What a run gave.
struct SimeonRun {
  SimeonState
      end;  ///< Simeon's 24 components at the end time (accelerations and multipliers there)
  double projected_position =
      0.0;                ///< the largest change of a position by the initial projection [m or rad]
  long dropped_rows = 0;  ///< constraint rows dropped as redundant
  long steps = 0;
  double wall_seconds = 0.0;
};

/// The crank (RigidBody: M1, J1 about its pivot, centre of mass at L1 / 2), `rod` (pinned at its
/// node "root" to the crank's tip, at "tip" to the slider) and the slider (a point mass on a
/// prismatic joint along W x), crank.f's driver phi1 = OMEGA t, no gravity; started from Simeon's
/// positions and velocities `start` (made consistent by mbs::Simulate's projection) and
/// integrated with `integrator` to `end_time` [s].
SimeonRun RunSimeonCrank(const SimeonCrankData& data, const sid::ReducedBody& rod,
                         const SimeonState& start, const mbs::OdeOptions& integrator,
                         double end_time);

}  // namespace flexmbs::validation
