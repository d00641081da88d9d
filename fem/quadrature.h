#pragma once

#include <Eigen/Core>

#include "fem/element_type.h"

namespace flexmbs::fem {

/// A quadrature rule on a reference domain: sum_q weights(q) f(points.col(q)).
struct QuadratureRule {
  Eigen::Matrix3Xd points;
  Eigen::VectorXd weights;
  int degree;  ///< every polynomial of this total degree (tensor degree for hexahedra) is exact
};

/// The rule used for the stiffness matrix of `type`: exact for B^T D B on an affine
/// (tetrahedra, wedges in-plane) or parallelepiped (hexahedra) element, and exact for det J of
/// any isoparametric (also curved) element, which is what makes every type pass the
/// constant-strain patch test on distorted and curved meshes (the quadrature volume must not
/// depend on interior node positions). Hence degree 3, not 2, for tet10 (det J is cubic).
///   tet4: 1 point (degree 1); tet10: 8 points (degree 3, Witherden & Vincent 2015);
///   hex8: 2x2x2 Gauss; hex20: 3x3x3 Gauss;
///   wedge6: 3-point triangle (degree 2) x 2-point Gauss; wedge15: 6-point triangle (degree 4)
///   x 3-point Gauss.
const QuadratureRule& StiffnessRule(ElementType type);

/// The stiffness rule for an element of `type` whose edges are straight with mid-edge nodes at
/// their midpoints (an affine tet10): there det J is constant and B^T D B of degree 2, so the
/// 4-point degree-2 rule is exact and half the cost of StiffnessRule. Equal to StiffnessRule
/// for every other type.
const QuadratureRule& AffineStiffnessRule(ElementType type);

/// The rule used for the consistent mass matrix (and for volume integrals) of `type`: exact
/// for N_a N_b on undistorted elements.
///   tet4: 4 points (degree 2); tet10: 14 points (degree 5, Walkington);
///   hex8: 2x2x2 Gauss; hex20: 3x3x3 Gauss; wedges as for stiffness.
const QuadratureRule& MassRule(ElementType type);

/// Gauss-Legendre rule with `n` (1..4) points on [-1, 1].
QuadratureRule GaussLine(int n);

}  // namespace flexmbs::fem
