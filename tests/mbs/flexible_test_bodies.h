#pragma once

// Small reduced bodies for the flexible-body tests, each with the FE model it came from, so a
// test can compute what the body should do node by node, independently of the SID invariants.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fem/material.h"
#include "fem/mesh.h"
#include "reduction/modal_basis.h"
#include "reduction/sid_spec.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs::testing {

/// A reduced body and its FE model.
struct FeReducedBody {
  fem::Mesh mesh;
  Eigen::SparseMatrix<double> K, M;  ///< consistent mass [N/m], [kg]
  reduction::ReducedBasis basis;
  reduction::SidSpec sid_spec;       ///< how `body` was built from `basis`
  sid::ReducedBody body;             ///< reduction::BuildReducedBody of the whole basis
};

/// Box dimensions of the test beam [m]: 0.6 x 0.1 x 0.08, 6 x 2 x 2 hex8 cells, steel.
inline const Eigen::Vector3d kBeamSize(0.6, 0.1, 0.08);

/// Rayleigh damping of the bodies: De = a Me + b Ke.
inline constexpr double kRayleighMassPerS = 3.0, kRayleighStiffnessS = 2e-5;

/// The beam clamped at x = 0 (support "root") with a rigid interface "tip" at x = L:
/// Craig-Bampton, 6 constraint modes then 4 fixed-interface normal modes. Nodes: "tip" (the
/// interface), "mid" (averaging, the plane x = L/2), "corner" (the FE node at (L/2, b, h)).
/// Contact surface "tip", Rayleigh damping, geometric stiffening computed.
const FeReducedBody& CraigBamptonBeam();

/// The same beam free-free: 6 rigid modes then 5 elastic ones; nodes "mid" and "corner",
/// contact surface "tip", Rayleigh damping, geometric stiffening computed (inertia relief).
const FeReducedBody& FreeFreeBeam();

/// The beam unsupported with the rigid interface "tip": Craig-Bampton, 6 constraint modes (a
/// rigid motion of the whole beam) then 3 normal modes; no stiffening.
const FeReducedBody& UnsupportedCraigBamptonBeam();

/// A free hex8 box [0, size] of `cells` cells and `material` with its consistent K and M, the
/// node sets `node_sets` (name -> FE nodes, found on the meshed box), the contact surfaces on
/// those of `surfaces`, no damping or stiffening, and its free-free modes below max_frequency_hz
/// (at most DOF - 6 of them); `body` left empty (Reduce makes it from a chosen basis).
FeReducedBody FreeFreeBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                          const fem::IsotropicMaterial& material,
                          const std::function<std::map<std::string, std::vector<int>>(const fem::Mesh&)>& node_sets,
                          const std::vector<std::string>& surfaces, double max_frequency_hz);

/// The columns of a basis whose kind is not rigid.
std::vector<Eigen::Index> ElasticColumns(const reduction::ReducedBasis& basis);

/// `basis` with only the columns `keep` (Phi, kinds, names, reduced matrices, frequencies,
/// residuals), as a reduction would have made it from those columns.
reduction::ReducedBasis KeepColumns(const reduction::ReducedBasis& basis, const std::vector<Eigen::Index>& keep);

/// BuildReducedBody of `basis` on `fe`'s mesh with `fe.sid_spec`.
sid::ReducedBody Reduce(const FeReducedBody& fe, const reduction::ReducedBasis& basis);

/// The symmetric D with w^T D w = -sum_l w_q,l a^T K0omega_l b for every w (w_q: the six
/// products w1^2, w2^2, w3^2, w1 w2, w2 w3, w3 w1), built by polarisation: the stiffening
/// field's inertia change dJ for a = b = q, half its rate for a = qdot, b = q
/// (mbs/stiffening_inertia.h), computed independently of it.
Eigen::Matrix3d CentrifugalInertiaChange(const sid::GeometricStiffening& K0, const Eigen::VectorXd& a,
                                         const Eigen::VectorXd& b);

}  // namespace flexmbs::mbs::testing
