#pragma once

#include <string>
#include <string_view>

namespace flexmbs::fem {

/// Isotropic linear elastic material (SI units).
struct IsotropicMaterial {
  std::string name;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.0;
  double density_kg_m3 = 0.0;

  /// Lame's first parameter lambda = E nu / ((1 + nu)(1 - 2 nu)) [Pa].
  double LameLambdaPa() const;
  /// Shear modulus mu = E / (2 (1 + nu)) [Pa].
  double ShearModulusPa() const;
};

/// Throws InputError "<where>: material '<name>': <what> <value> must be ..." unless
/// E > 0, -1 < nu < 0.5 and rho > 0 (all finite).
void ValidateMaterial(const IsotropicMaterial& material, std::string_view where);

}  // namespace flexmbs::fem
