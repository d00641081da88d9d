#include "fem/material.h"

#include <cmath>
#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::fem {

double IsotropicMaterial::LameLambdaPa() const {
  return youngs_modulus_pa * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

double IsotropicMaterial::ShearModulusPa() const {
  return youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio));
}

void ValidateMaterial(const IsotropicMaterial& m, std::string_view where) {
  auto fail = [&](std::string_view what, double value, std::string_view rule) {
    throw InputError(fmt::format("{}: material '{}': {} {:g} {}", where, m.name, what, value, rule));
  };
  if (!std::isfinite(m.youngs_modulus_pa) || m.youngs_modulus_pa <= 0.0) {
    fail("Young's modulus", m.youngs_modulus_pa, "must be > 0");
  }
  if (!std::isfinite(m.poisson_ratio) || m.poisson_ratio <= -1.0 || m.poisson_ratio >= 0.5) {
    fail("Poisson's ratio", m.poisson_ratio, "must be in (-1, 0.5)");
  }
  if (!std::isfinite(m.density_kg_m3) || m.density_kg_m3 <= 0.0) {
    fail("density", m.density_kg_m3, "must be > 0");
  }
}

}  // namespace flexmbs::fem
