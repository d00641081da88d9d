#pragma once
// Compliant normal contact laws (docs/contact.md, "Compliant laws"): the normal force of a
// contact as a function of its penetration delta [m] and penetration rate delta' [m/s], with
// its analytic derivatives. Plain data, no bodies: contact/ never uses mbs/.

namespace flexmbs::contact {

/// Which compliant law a NormalLaw is (each one's source at its factory below).
enum class NormalLawKind {
  kLinear,              ///< spring-dashpot k delta^n + c delta' (n = 1: linear penalty)
  kHertz,               ///< elastic Hertz k delta^(3/2)
  kHuntCrossley,        ///< k delta^(3/2) (1 + chi delta'), chi = 3 (1 - e) / (2 v0)
  kLankaraniNikravesh,  ///< chi = 3 (1 - e^2) / (4 v0)
  kFlores,              ///< chi = 8 (1 - e) / (5 e v0)
};

/// The law's name as a scene file writes it: linear, hertz, hunt_crossley,
/// lankarani_nikravesh, flores.
const char* Name(NormalLawKind kind);

/// A normal force and its partial derivatives at (delta, delta').
struct NormalForce {
  double force = 0.0;     ///< F_N >= 0 [N]: pushes the two bodies apart
  double d_delta = 0.0;   ///< dF_N/d delta [N/m]
  double d_rate = 0.0;    ///< dF_N/d delta' [N s/m]
};

/// A compliant normal law of the one form that covers all five kinds,
///   F_N = max(0, k delta^n (1 + chi delta') + c delta')   for delta > 0, 0 otherwise,
/// clipped at 0 so that the contact never pulls (a dashpot would at the end of a rebound).
/// Build it with the factories below, which check the parameters.
struct NormalLaw {
  NormalLawKind kind = NormalLawKind::kLinear;
  double stiffness = 0.0;   ///< k [N/m^n]
  double exponent = 1.0;    ///< n >= 1
  double damping = 0.0;     ///< c [N s/m]: a linear dashpot (kLinear only)
  double hysteresis = 0.0;  ///< chi [s/m]: hysteresis damping factor (Hunt-Crossley family)
  double restitution = 1.0; ///< e the hysteresis was built for (1 for kLinear, kHertz)
};

/// F_N = k delta^n + c delta' (clipped at 0): a power spring with a linear dashpot; n = 1 is the
/// linear penalty (Kelvin-Voigt) law. k >= 0 [N/m^n], c >= 0 [N s/m], n >= 1; InputError naming
/// the parameter and its value otherwise.
NormalLaw LinearLaw(double stiffness, double damping, double exponent = 1.0);

/// F_N = k delta^(3/2): Hertz's elastic contact of two spheres or a sphere and a flat
/// (K. L. Johnson, Contact Mechanics, Cambridge 1985, sec. 4.2), with k = HertzStiffness(...)
/// (contact/laws/hertz.h). k >= 0 [N/m^1.5].
NormalLaw HertzLaw(double stiffness);

/// F_N = k delta^(3/2) (1 + chi delta'), chi = 3 (1 - e) / (2 v0): K. H. Hunt, F. R. E. Crossley,
/// "Coefficient of restitution interpreted as damping in vibroimpact", J. Appl. Mech. 42 (1975)
/// 440-445. Derived for e near 1 (first order in 1 - e). k >= 0, 0 < e <= 1, impact speed
/// v0 > 0 [m/s] (the approach speed the law is tuned for).
NormalLaw HuntCrossleyLaw(double stiffness, double restitution, double impact_speed);

/// chi = 3 (1 - e^2) / (4 v0): H. M. Lankarani, P. E. Nikravesh, "A contact force model with
/// hysteresis damping for impact analysis of multibody systems", J. Mech. Des. 112 (1990)
/// 369-376. From the energy balance of the hysteresis loop; meant for e near 1.
NormalLaw LankaraniNikraveshLaw(double stiffness, double restitution, double impact_speed);

/// chi = 8 (1 - e) / (5 e v0): P. Flores, M. Machado, M. T. Silva, J. M. Martins, "On the
/// continuous contact force models for soft materials in multibody dynamics", Multibody Syst.
/// Dyn. 25 (2011) 357-375. For any e in (0, 1].
NormalLaw FloresLaw(double stiffness, double restitution, double impact_speed);

/// The law at penetration delta [m] and rate delta' [m/s] (> 0: approaching). Zero force and
/// derivatives for delta <= 0 and where the law would pull.
NormalForce Evaluate(const NormalLaw& law, double penetration, double penetration_rate);

/// The restitution e_eff = v_out / v0 the law gives on a single-DOF impact at approach speed
/// v0 > 0 [m/s], exactly: m v dv / (1 + chi v) = -k delta^n d delta integrates over the impact
/// (delta from 0 back to 0) to chi v_out - ln(1 + chi v_out) = chi v0 - ln(1 + chi v0) with
/// v_out = -e_eff v0, a function of chi v0 alone (the law never clips on the way, since
/// 1 + chi v > 0 throughout). 1 for Hertz. Precondition: no linear dashpot (damping == 0).
double ImpactRestitution(const NormalLaw& law, double impact_speed);

/// The energy stored in the law's spring, k delta^(n+1) / (n+1) [J] for delta > 0, else 0.
double ElasticEnergy(const NormalLaw& law, double penetration);

}  // namespace flexmbs::contact
