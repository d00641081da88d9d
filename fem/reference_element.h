#pragma once

#include <Eigen/Core>

#include "fem/element_type.h"

namespace flexmbs::fem {

/// Shape functions N_a(xi) of one element type on its reference domain, in gmsh node order.
///
/// Reference domains (gmsh's): tetrahedra on the unit simplex {xi, eta, zeta >= 0,
/// xi + eta + zeta <= 1}; hexahedra on [-1, 1]^3; wedges on the unit triangle in (xi, eta)
/// times [-1, 1] in zeta. Each space is spanned by a monomial basis (complete P1/P2 for
/// tetrahedra, Q1 and the 20-term serendipity space for hexahedra, P1 x Q1 and the 15-term
/// serendipity space for wedges), and N_a is the Lagrange basis dual to the nodes
/// (N_a(xi_b) = delta_ab), obtained from the inverse Vandermonde matrix.
class ReferenceElement {
 public:
  /// The reference element of `type`; built once, shared, thread-safe to read.
  static const ReferenceElement& Of(ElementType type);

  ElementType type() const { return type_; }
  int num_nodes() const { return static_cast<int>(nodes_.cols()); }

  /// Reference coordinates of the nodes, one column each.
  const Eigen::Matrix3Xd& nodes() const { return nodes_; }

  /// Values N (num_nodes) and reference gradients dN (3 x num_nodes, dN(i, a) = dN_a/dxi_i)
  /// at the reference point `xi`.
  void Evaluate(const Eigen::Vector3d& xi, Eigen::VectorXd* N, Eigen::Matrix3Xd* dN) const;

 private:
  ReferenceElement(ElementType type, Eigen::Matrix3Xd nodes, Eigen::Matrix3Xi exponents);

  ElementType type_;
  Eigen::Matrix3Xd nodes_;
  Eigen::Matrix3Xi exponents_;  ///< monomial k is xi^e(0,k) eta^e(1,k) zeta^e(2,k)
  Eigen::MatrixXd coefficients_;  ///< N_a = sum_k coefficients_(k, a) * monomial_k
};

}  // namespace flexmbs::fem
