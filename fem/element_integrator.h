#pragma once

#include <Eigen/Core>
#include <vector>

#include "fem/element_type.h"
#include "fem/material.h"

namespace flexmbs::fem {

struct QuadratureRule;

/// How the element mass matrix is formed.
enum class MassMatrixKind {
  kConsistent,  ///< M_ab = int rho N_a N_b dV
  kLumped,      ///< HRZ diagonal lumping (Hinton, Rock, Zienkiewicz 1976): positive for tet10
};

/// The linear-elastic (Cauchy) stress sigma = lambda tr(eps) I + 2 mu eps [Pa] of the
/// displacement gradient grad_u (i, k) = du_i/dx_k, eps = (grad_u + grad_u^T) / 2.
Eigen::Matrix3d LinearElasticStress(const Eigen::Matrix3d& grad_u, const IsotropicMaterial& material);

/// Computes element stiffness and mass matrices of one element type for isotropic linear
/// elasticity. Shape functions are tabulated once at the quadrature points; one integrator per
/// thread. Element DOF 3 a + i is node a along axis i.
class ElementIntegrator {
 public:
  explicit ElementIntegrator(ElementType type);

  ElementType type() const { return type_; }
  int num_nodes() const { return num_nodes_; }

  /// Stiffness K_e (3n x 3n) [N/m] of the element with node coordinates X (3 x n) [m]:
  /// K_e = sum_q w_q det J_q B_q^T D B_q with the isotropic D. Returns the smallest det J at
  /// the quadrature points; the element is valid only if it is > 0.
  double Stiffness(const Eigen::Matrix3Xd& X, const IsotropicMaterial& material,
                   Eigen::MatrixXd* K_e);

  /// Scalar mass matrix m_e (n x n) [kg]: m_ab = int rho N_a N_b dV (consistent) or its HRZ
  /// diagonal (lumped). The 3n x 3n element mass is m_e (x) I_3. Returns the smallest det J.
  double ScalarMass(const Eigen::Matrix3Xd& X, double density_kg_m3, MassMatrixKind kind,
                    Eigen::MatrixXd* m_e);

  /// The points of the geometric-stiffness rule (below) on the element with node coordinates
  /// X (3 x n) [m]: per point q, weights(q) = w_q det J_q [m^3] and gradients[q] the physical
  /// shape-function gradients (3 x n, (i, a) = dN_a/dx_i) [1/m]. Returns the smallest det J.
  ///
  /// The rule integrates grad N_a^T sigma grad N_b exactly when sigma is the stress of a
  /// displacement field of the element's own space (sigma, like grad N, one degree below the
  /// displacement) and the element is straight-sided (an affine image of the reference element:
  /// det J constant, gradients of the reference degree): the integrand is then a polynomial of
  /// three factors of the gradient's degree.
  ///   tet4: 1 point (degree 0 integrand); tet10: the 8-point degree-3 rule;
  ///   hex8: 2x2x2 Gauss (tensor degree 3); hex20: 4x4x4 Gauss (serendipity gradients are of
  ///   degree 2 per coordinate, so the integrand is of degree 6 per coordinate);
  ///   wedge6: collapsed 3x3 Gauss triangle (degree 4 >= 3) x 2-point Gauss (degree 3);
  ///   wedge15: collapsed 4x4 Gauss triangle (degree 6) x 4-point Gauss (degree 7).
  /// On curved or distorted elements (non-constant det J) it is a quadrature of the same cost,
  /// not exact.
  double GeometricStiffnessPoints(const Eigen::Matrix3Xd& X, Eigen::VectorXd* weights,
                                  std::vector<Eigen::Matrix3Xd>* gradients);

  /// Scalar geometric (stress) stiffness k_G (n x n) [N/m] of the element in the stress
  /// sigma(u_e) of its nodal displacements u_e (3 x n) [m] (column a: node a; stress by
  /// LinearElasticStress at each point of GeometricStiffnessPoints):
  ///     k_ab = int grad N_a^T sigma grad N_b dV,   K_G,e = k_G (x) I_3 (DOF 3 a + i),
  /// so that u^T K_G,e v = int sum_i grad u_i . (sigma grad v_i) dV (Cook, Malkus, Plesha &
  /// Witt, "Concepts and Applications of Finite Element Analysis", 4th ed. 2002, ch. 18;
  /// Bathe, "Finite Element Procedures", 1996, sec. 6.3). Positive for tension. Exact for
  /// straight-sided elements (see GeometricStiffnessPoints). Returns the smallest det J.
  double ScalarGeometricStiffness(const Eigen::Matrix3Xd& X, const IsotropicMaterial& material,
                                  const Eigen::Matrix3Xd& u_e, Eigen::MatrixXd* k_G);

  /// The same for a uniform stress sigma [Pa] (symmetric 3 x 3, in B).
  double ScalarGeometricStiffness(const Eigen::Matrix3Xd& X, const Eigen::Matrix3d& sigma,
                                  Eigen::MatrixXd* k_G);

  /// Mass-weighted volume moments of the element: mass [kg], first moment int rho x dV
  /// [kg m] and second moment int rho x x^T dV [kg m^2], by the mass rule directly from the
  /// geometry (independently of any mass matrix). Returns the smallest det J.
  double VolumeMoments(const Eigen::Matrix3Xd& X, double density_kg_m3, double* mass,
                       Eigen::Vector3d* first, Eigen::Matrix3d* second);

 private:
  struct Tabulation {
    Eigen::VectorXd weights;
    std::vector<Eigen::VectorXd> N;
    std::vector<Eigen::Matrix3Xd> dN;  ///< reference gradients
  };
  static Tabulation Tabulate(ElementType type, const QuadratureRule& rule);
  /// k_G of the stress stress_at(g) at each geometric-stiffness point (g: the gradients there).
  template <class StressAt>
  double GeometricStiffnessOf(const Eigen::Matrix3Xd& X, StressAt stress_at, Eigen::MatrixXd* k_G);
  /// True for a tet10 whose mid-edge nodes sit at their edge midpoints (an affine element).
  bool IsAffineTet10(const Eigen::Matrix3Xd& X) const;

  ElementType type_;
  int num_nodes_;
  Tabulation stiffness_tab_;
  Tabulation affine_stiffness_tab_;  ///< the cheaper exact rule for affine tet10
  Tabulation mass_tab_;
  Tabulation geometric_tab_;  ///< the geometric-stiffness rule (GeometricStiffnessPoints)
  Eigen::VectorXd point_weights_;              ///< scratch: GeometricStiffnessPoints
  std::vector<Eigen::Matrix3Xd> point_grads_;  ///< scratch: GeometricStiffnessPoints
  Eigen::Matrix3Xd grad_;  ///< scratch: physical gradients at one point
};

}  // namespace flexmbs::fem
