#pragma once

// The small rotation of the material at one FE node, for marker nodes coupled to a single
// node (sid::Node psi).

#include <Eigen/Core>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// The infinitesimal rotation psi = 1/2 curl u at FE node `node` for each displacement field
/// (column) of `Phi` (3 num_nodes x n, DOF 3 node + axis): a 3 x n matrix [rad per unit column].
/// In each element e that holds the node, the displacement gradient at the node is exact for
/// the element's interpolation: psi_e = 1/2 sum_a grad N_a(x_node) x u_a (gradients from the
/// reference element at the node's reference coordinates and the element Jacobian there).
/// The node's value is the average of psi_e weighted by element volume, so that small (often
/// poorly shaped) elements count less. Exact, for every element type and any mesh, for fields in
/// every element's space; in particular a rigid rotation u = theta x x gives theta, and a linear
/// symmetric strain field u = E x gives 0.
/// Preconditions: `node` in range, Phi.rows() == mesh.num_dofs(). Throws InputError if no
/// element holds the node, or an element's Jacobian at the node is not positive.
Eigen::MatrixXd NodalRotation(const Mesh& mesh, int node, const Eigen::MatrixXd& Phi);

}  // namespace flexmbs::fem
