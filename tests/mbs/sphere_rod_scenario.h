#pragma once
// A steel sphere striking the centre of the end face of a free steel rod (tests/mbs/
// sphere_rod_impact_test.cc, bench/contact_speed_bench.cc): the rod's FE model and free-free
// modes, the full FE model with a Hertz spring integrated without any multibody code
// (tests/mbs/hertz_rod_model.h), and the reduced rod with the compliant sphere_surface element
// integrated by flexmbs, both sampled at the same output times.

#include <Eigen/Core>
#include <vector>

#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs::testing {

/// The scenario's sizes: a rod of length x side x side [m] meshed by cells hex8 cells (x, y, z),
/// steel (E = 210 GPa, nu = 0.3), struck at speed [m/s] by a steel sphere of radius [m], sampled
/// every output [s] to end_time [s]; the rod's free-free modes are computed up to
/// axial_band c / (2 L) (the band's axial mode count).
struct SphereRodSetup {
  double length = 0.5, side = 0.02;
  Eigen::Vector3i cells{100, 1, 1};
  double radius = 0.01, speed = 1.0;
  double end_time = 120e-6, output = 0.25e-6;
  double axial_band = 16.5;
};

/// The rod with its modes, the contact point's weights b on the FE DOFs (the end face's centre,
/// along x: the centre node, or the mean of the nodes around it) and Hertz's stiffness [N/m^1.5].
struct SphereRod {
  SphereRodSetup setup;
  FeReducedBody rod;
  Eigen::VectorXd b;
  std::vector<int> contact_nodes;  ///< the nodes b weighs
  double sphere_mass = 0.0, hertz_stiffness = 0.0;
};

/// Meshes, assembles and reduces the rod of `setup` (contact surface "end": the face x = 0).
SphereRod MakeSphereRod(const SphereRodSetup& setup);

/// A force history at the output times k output, k = 1, 2, ...
struct ForceHistory {
  std::vector<double> force;   ///< [N]
  double seconds = 0.0;        ///< wall time of the integration
  double highest_mode_hz = 0.0;
};

/// The full FE model, Newmark's rule at output / substeps.
ForceHistory FullSphereRod(const SphereRod& scenario, int substeps);

/// The reduced rod with its lowest `modes` loaded modes (b^T phi != 0: bending and torsion vanish
/// by symmetry), plus the static correction mode of the contact load if `correction`, and the
/// sphere on its contact surface (Hertz), by flexmbs' implicit ODE method at relative tolerance
/// rtol.
ForceHistory ReducedSphereRod(const SphereRod& scenario, int modes, bool correction, double rtol);

/// The largest force [N], the time from the first to the last output with force [s], and
/// max_k |a_k - b_k| / Peak(b) over the common outputs.
double Peak(const ForceHistory& history);
double Duration(const ForceHistory& history, double output);
double HistoryError(const ForceHistory& a, const ForceHistory& b);

/// Hertz's contact time of the sphere on a rigid half-space at the scenario's speed [s]
/// (Johnson, "Contact Mechanics", 1985, §11.4): 2.94 (5 m v^2 / (4 k))^(2/5) / v.
double HertzContactTime(const SphereRod& scenario);

}  // namespace flexmbs::mbs::testing
