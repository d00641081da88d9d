#include "contact/laws/hertz.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace flexmbs::contact {

void CheckMaterial(const char* what, const ElasticMaterial& material) {
  if (!(material.youngs_modulus > 0.0) || !std::isfinite(material.youngs_modulus)) {
    throw InputError(fmt::format("{}: Young's modulus {} must be finite and > 0", what, material.youngs_modulus));
  }
  if (!(material.poissons_ratio > -1.0 && material.poissons_ratio < 0.5)) {
    throw InputError(fmt::format("{}: Poisson's ratio {} must be in (-1, 0.5)", what, material.poissons_ratio));
  }
}

double EffectiveModulus(const ElasticMaterial& body1, const ElasticMaterial& body2) {
  const auto compliance = [](const ElasticMaterial& m) {
    return (1.0 - m.poissons_ratio * m.poissons_ratio) / m.youngs_modulus;
  };
  return 1.0 / (compliance(body1) + compliance(body2));
}

double EffectiveModulusOnRigid(const ElasticMaterial& body) {
  return body.youngs_modulus / (1.0 - body.poissons_ratio * body.poissons_ratio);
}

double EffectiveRadius(double radius1, double radius2) { return radius1 * radius2 / (radius1 + radius2); }

double HertzStiffness(double effective_modulus, double effective_radius) {
  return 4.0 / 3.0 * effective_modulus * std::sqrt(effective_radius);
}

}  // namespace flexmbs::contact
