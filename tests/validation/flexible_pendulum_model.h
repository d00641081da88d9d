#pragma once
// The flexible pendulum shared by tests/validation/flexible_pendulum_test.cc and
// bench/flexible_pendulum_bench.cc: a slender steel link clamped in a hub that turns on a
// horizontal revolute joint. A brake on the hub holds the link horizontal (a cantilever bent by
// gravity) and opens over a short time; the link then swings down and vibrates.
//
// Link body frame B: x along the link (root face centre at Bo, tip at x = L), y the in-plane
// transverse direction (the thin side: the swing bends the link along y), z the hinge axis (the
// wide side). The root face is clamped in every mode, so it moves with B, which the hub holds.
//
// The complete basis: every eigenvector of the clamped K, M (a dense solve), expanded by zeros
// on the root face. It spans every FE displacement that keeps the root face in the hub, so the
// floating-frame body with all of it is the linear-elastic FE model of the link in its hub,
// integrated directly; its first n columns are the reduced models.
//
// The hub. The complete basis spans every motion of the link except the root face's, so on its
// own the hinge rotation would carry only the root face's inertia: the hinged system's
// effective inertia J_zz - Cr_z^T Me^-1 Cr_z falls to that of one face of nodes, its highest
// frequency rises far above Ke's (the root face rattling against the rest), and the implicit
// integrator's Newton iteration stalls (measured: the step size collapses as the kept modes
// approach the complete set). A real hinge has a hub; its inertia (0.6 % of the link's about the
// hinge) keeps the effective inertia finite. Every model, reduced or full, swings with it.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "fem/mesh.h"
#include "mbs/multibody_system.h"
#include "mbs/ode_integrator.h"
#include "mbs/simulation.h"
#include "reduction/modal_basis.h"
#include "sid/reduced_body.h"

namespace flexmbs::validation {

/// The link's size [m] and its hex20 mesh: cells along x, y, z.
struct LinkGeometry {
  double length = 1.0;      ///< L along x
  double thickness = 5e-3;  ///< along y, in the plane of the swing
  double width = 10e-3;     ///< along z, the hinge axis
  Eigen::Vector3i cells{6, 1, 1};
};

/// The meshed link, its FE matrices and its complete clamped basis.
struct FeLink {
  LinkGeometry geometry;
  fem::Mesh mesh;                     ///< node sets "root" (x = 0) and "tip" (x = L)
  Eigen::SparseMatrix<double> K, M;   ///< [N/m], consistent [kg]
  std::vector<int> free_dofs;         ///< the DOF off the root face, ascending
  /// Every clamped eigenpair: lambda ascending [rad^2/s^2] and the basis (Phi M-orthonormal,
  /// zero on the root face; K_reduced, M_reduced the library's Phi^T K Phi, Phi^T M Phi).
  Eigen::VectorXd eigenvalues;
  reduction::ReducedBasis basis;
  /// The SID body of the complete basis: marker "tip" (averaging over the tip face, at its
  /// centre), no damping, no geometric stiffening.
  sid::ReducedBody body;
};

/// Steel (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3): meshes, assembles, solves the clamped
/// eigenproblem densely and builds the SID body.
FeLink BuildLink(const LinkGeometry& geometry);

/// `body` with its first n modes (mbs::RestrictModes).
sid::ReducedBody FirstModes(const sid::ReducedBody& body, Eigen::Index n);

/// The hub: a steel disc on the hinge axis, centred on the hinge (defaults: 0.99 kg,
/// 7.9e-4 kg m^2 about its axis).
struct Hub {
  double radius = 0.04;      ///< [m]
  double thickness = 0.025;  ///< [m], along the axis
};

/// How a pendulum run is released and integrated.
struct SwingOptions {
  /// The brake's opening time t_r [s]: its torque falls from the holding torque to 0 by a
  /// quintic smooth step over [0, t_r], slowly for the modes above ~100 Hz (quasi-static), fast
  /// for the first bending mode (the link springs back and vibrates).
  double release_time = 0.02;
  Hub hub;
  double end_time = 1.0;          ///< [s]
  double output_interval = 2e-3;  ///< [s]
  mbs::OdeOptions integrator;
};

/// A swing's recorded history at the output times.
struct Swing {
  std::vector<double> time;            ///< [s]
  /// The tip marker's elastic displacement along B's y (transverse to the link, in the swing's
  /// plane): (R_WB^T (p_W,tip - p_WBo_W) - p_BoTip_B(0))_y [m].
  std::vector<double> tip_deflection;
  /// The hinge angle: the rotation of B from its start about the hinge axis [rad], unwrapped.
  std::vector<double> hinge_angle;
  std::vector<double> energy;          ///< kinetic + potential of hub and link [J]
  long steps = 0, rhs_evaluations = 0;
  double cpu_seconds = 0.0;            ///< process CPU time of the integration
};

/// The CPU time of this process [s] (CLOCK_PROCESS_CPUTIME_ID), for timing runs.
double ProcessCpuSeconds();

/// mbs::Simulate from t = 0 with `integrator`, `end_time` and `output_interval`; the process CPU
/// time it took goes to `cpu_seconds`.
mbs::SimulationStatistics SimulateTimed(mbs::MultibodySystem& system, const mbs::OdeOptions& integrator,
                                        double end_time, double output_interval, const Eigen::VectorXd& y0,
                                        const mbs::OutputCallback& record, double* cpu_seconds);

/// The static deflection of the held link (hub at rest, link horizontal): the modal
/// coordinates with Ke q = Ct R0^T g_W, the elastic row at rest.
Eigen::VectorXd HeldDeflection(const sid::ReducedBody& body);

/// Releases the pendulum made of `body` (any mode selection of the link; geometric stiffening
/// off) from its held deflection at rest, the link along W x and the hinge axis along W y,
/// gravity -9.81 W z, and records the swing.
Swing RunSwing(const sid::ReducedBody& body, const SwingOptions& options);

/// The largest differences of a swing from a reference at the same output times: tip deflection
/// [m] and hinge angle [rad].
struct SwingDeviation {
  double tip_deflection = 0.0;
  double hinge_angle = 0.0;
};
SwingDeviation Deviation(const Swing& swing, const Swing& reference);

/// max |w(t)| [m] over the swing.
double LargestTipDeflection(const Swing& swing);

/// The largest change of the energy [J] from its value at the release time: the brake does work
/// before, nothing does after (no damping).
double EnergyDriftAfterRelease(const Swing& swing, double release_time);

/// The gravitational energy the link releases from horizontal to hanging, m g x_cm [J]: the
/// scale of the swing's kinetic energy.
double SwingEnergyScale(const sid::ReducedBody& body);

}  // namespace flexmbs::validation
