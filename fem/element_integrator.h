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
  /// True for a tet10 whose mid-edge nodes sit at their edge midpoints (an affine element).
  bool IsAffineTet10(const Eigen::Matrix3Xd& X) const;

  ElementType type_;
  int num_nodes_;
  Tabulation stiffness_tab_;
  Tabulation affine_stiffness_tab_;  ///< the cheaper exact rule for affine tet10
  Tabulation mass_tab_;
  Eigen::Matrix3Xd grad_;  ///< scratch: physical gradients at one point
};

}  // namespace flexmbs::fem
