#pragma once
// Hertz's contact stiffness from the materials and the geometry of the two bodies
// (K. L. Johnson, Contact Mechanics, Cambridge 1985, sec. 4.2, eqs. 4.22-4.23): the normal
// force of two elastic spheres (or a sphere and a flat) is F = 4/3 E* sqrt(R*) delta^(3/2).

namespace flexmbs::contact {

/// An isotropic elastic material: Young's modulus E > 0 [Pa], Poisson's ratio -1 < nu < 0.5.
struct ElasticMaterial {
  double youngs_modulus = 0.0;   ///< E [Pa]
  double poissons_ratio = 0.0;   ///< nu [-]
};

/// Throws InputError "<what>: Young's modulus <E> must be finite and > 0" or "...: Poisson's
/// ratio <nu> must be in (-1, 0.5)" for a material out of range.
void CheckMaterial(const char* what, const ElasticMaterial& material);

/// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa] (Johnson eq. 4.22). Preconditions: CheckMaterial.
double EffectiveModulus(const ElasticMaterial& body1, const ElasticMaterial& body2);
/// E* of an elastic body against a rigid one: E / (1 - nu^2) [Pa].
double EffectiveModulusOnRigid(const ElasticMaterial& body);

/// 1/R* = 1/R1 + 1/R2 [m] for two spheres of radii R1, R2 > 0 (Johnson eq. 4.23); a sphere on a
/// flat has R* = R1 (R2 -> infinity).
double EffectiveRadius(double radius1, double radius2);

/// k = 4/3 E* sqrt(R*) [N/m^1.5] (Johnson eq. 4.23: F = 4/3 E* R*^(1/2) delta^(3/2)), E* [Pa] and
/// R* [m] > 0.
double HertzStiffness(double effective_modulus, double effective_radius);

}  // namespace flexmbs::contact
