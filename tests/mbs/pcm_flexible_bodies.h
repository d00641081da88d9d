#pragma once
// Clamped reduced bodies for the Polygonal Contact Model's flexible tests, with the FE model they
// came from, a static equilibrium of chosen coordinates by Newton's method on central
// differences, and the FE model's own static response to the contact loads as PCM spreads them
// (computed here, without the multibody code): the references of tests/mbs/pcm_flexible_test.cc.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "contact/pcm/foundation.h"
#include "mbs/multibody_system.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs::testing {

/// A steel hex8 box [0, size] of `cells` clamped at the nodes `clamped(mesh)` returns, with the
/// contact surface `surface` (the boundary faces of the node set `surface_nodes(mesh)`), reduced
/// to `normal_modes` fixed-interface modes and the attachment modes (a unit force along x, y and
/// z at each node alone, reduction::LoadDistribution::kPerNode) of the nodes `loaded(mesh)` (none
/// if it returns none): the static response to any load on those nodes is then the FE model's. `fe.body` is the reduced
/// body, named `name`.
struct ClampedBox {
  FeReducedBody fe;
  std::vector<int> clamped;  ///< the clamped FE nodes
};
using NodeSelection = std::function<std::vector<int>(const fem::Mesh&)>;
ClampedBox MakeClampedBox(const std::string& name, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                          const NodeSelection& clamped, const std::string& surface, const NodeSelection& surface_nodes,
                          const NodeSelection& loaded, int normal_modes);

/// The nodes on the four side faces x = 0, x = side_x, y = 0, y = side_y of a box's mesh, sorted,
/// each once: a plate clamped at its sides.
std::vector<int> SideFaceNodes(const fem::Mesh& mesh, double side_x, double side_y);

/// The nodes of `mesh` in the box [lo, hi] (component-wise, within 1e-12).
std::vector<int> NodesInBox(const fem::Mesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// One unknown of a static equilibrium: a coordinate and the row of h that must vanish.
struct Unknown {
  Eigen::Index position;  ///< index into y's positions
  Eigen::Index velocity;  ///< index into the velocities (h's row)
};
/// Body b's translation along `axis` (0, 1, 2) and its modal coordinates.
Unknown Translation(const MultibodySystem& system, int b, int axis);
std::vector<Unknown> ModalCoordinates(const MultibodySystem& system, int b);

/// Solves h_k(y) + extra_k = 0 for the coordinates of `unknowns`, all velocities zero, by
/// Newton's method with a Jacobian of central differences (step `step`), until the largest
/// residual is below `tolerance` [N]; returns the number of iterations, or -1 after 30 without
/// convergence. `y` is updated in place.
int SolveStatics(const MultibodySystem& system, const std::vector<Unknown>& unknowns, const Eigen::VectorXd& extra,
                 double step, double tolerance, Eigen::VectorXd& y);

/// One side of a PCM pair for the reference: the reduced body's surface (its triangles as the
/// element splits them), the body's frame in W, its modal coordinates and its FE model; or a rigid
/// mesh (box and surface null, q empty).
struct ReferenceSide {
  const ClampedBox* box;
  const sid::ContactSurface* surface;
  contact::PolygonMesh triangles_B;  ///< the surface's triangles, undeformed, in B (a rigid mesh's in its frame)
  Eigen::Vector3d p_WBo_W;
  Eigen::Matrix3d R_WB;
  Eigen::VectorXd q;
};

/// The nodal loads (3 N, in B) [N] that the pair's elements put on each side: every element of
/// A's triangles under B's (all pairs tried, no hierarchy) with its foundation force F at zero
/// velocity, spread over its faces' vertices by the element's weights (F on A's, -F on B's),
/// each vertex onto its FE node (none for a rigid side).
std::array<Eigen::VectorXd, 2> ReferenceNodalLoads(const ReferenceSide& A, const ReferenceSide& B,
                                                   const contact::ElasticFoundation& law, double max_depth);

/// The FE model's static displacements (3 N) [m] under nodal loads f with the clamped nodes held:
/// K_ff u_f = f_f by a sparse Cholesky factorisation.
Eigen::VectorXd ClampedStaticResponse(const ClampedBox& box, const Eigen::VectorXd& f);

}  // namespace flexmbs::mbs::testing
