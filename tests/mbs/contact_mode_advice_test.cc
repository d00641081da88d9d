// The mode advice (mbs/contact_mode_advice.h, docs/contact.md "Which modes a contact needs") on
// the pair types beyond sphere_surface_contact: the power law's contact time against its closed
// forms and SciPy's quadrature, a compliant surface_plane_contact on a free box (the points that
// touch first in parallel, the rigid effective mass of an eccentric touch, the law's scaling), and
// a unilateral surface_plane on a free bar (the lowest loaded mode's period, 2L/c).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "contact/laws/normal_law.h"
#include "core/rotation.h"
#include "mbs/contact_mode_advice.h"
#include "mbs/contact_mode_advice_pcm.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/rigid_body.h"
#include "mbs/surface_contact_force.h"
#include "mbs/surface_unilateral.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs {
namespace {

using testing::FeReducedBody;

// --- the power law's contact time ---------------------------------------------------------------

/// t_c v / delta_m = 2 int_0^1 dx / sqrt(1 - x^(n+1)), by scipy.integrate.quad (estimated error
/// 1e-10) for n = 1, 3/2, 2.
TEST(ContactModeAdvice, PowerLawContactTimeIsTheEnergyBalancesIntegral) {
  const double m = 0.7, v = 1.3, k = 2e9;
  for (const auto& [n, scipy] : std::map<double, double>{{1.0, 3.141592653589788}, {1.5, 2.943275184324214},
                                                          {2.0, 2.8043642106517854}}) {
    const double delta_m = std::pow((n + 1.0) * m * v * v / (2.0 * k), 1.0 / (n + 1.0));
    EXPECT_NEAR(PowerLawContactTime(m, v, k, n) * v / delta_m, scipy, 1e-11) << n;  // measured 8.8e-13 (n = 2)
  }
  // The closed forms: pi sqrt(m / k) for the linear spring; Hertz's (Johnson 1985, §11.4, 2.94 rounded).
  EXPECT_NEAR(PowerLawContactTime(m, v, k, 1.0) / (std::numbers::pi * std::sqrt(m / k)), 1.0, 1e-14);  // round-off
  EXPECT_NEAR(PowerLawContactTime(m, v, k, 1.5) / (2.94 * std::pow(5.0 * m * v * v / (4.0 * k), 0.4) / v), 1.0,
              2e-3);  // 2.9433 / 2.94
}

// --- a compliant surface_plane_contact on a free box ----------------------------------------------

constexpr double kA = 0.2, kB = 0.1, kC = 0.08;  // the box [m]

/// A free steel box [0, a] x [0, b] x [0, c], 4 x 2 x 2 hex8, contact surface "bottom" (z = 0,
/// 5 x 3 vertices), its free-free modes below 20 kHz.
const FeReducedBody& Box() {
  static const FeReducedBody box = testing::FreeFreeBox(
      Eigen::Vector3i(4, 2, 2), Eigen::Vector3d(kA, kB, kC), flexmbs::testing::Steel(),
      [](const fem::Mesh& mesh) {
        return std::map<std::string, std::vector<int>>{{"bottom", flexmbs::testing::NodesOnPlane(mesh, 2, 0.0)}};
      },
      {"bottom"}, 20e3);
  return box;
}

double BoxMass() { return flexmbs::testing::Steel().density_kg_m3 * kA * kB * kC; }

/// The box, turned by R_WB about its centre of mass and 1 mm above the ground plane z = 0 at its
/// lowest vertex, moving down at `speed`, on the contact `floor(origin, bottom, modes)` makes
/// (the box's frame marker, its bottom surface and its number of modes).
struct BoxOnPlane {
  MultibodySystem system{Eigen::Vector3d::Zero()};
  Eigen::VectorXd y;
};
using FloorFactory =
    std::function<std::unique_ptr<ForceElement>(const MarkerRef&, const sid::ContactSurface&, Eigen::Index)>;

std::unique_ptr<BoxOnPlane> MakeBox(const Eigen::Matrix3d& R_WB, double speed, const FloorFactory& floor) {
  const FeReducedBody& fe = Box();
  sid::ReducedBody data = testing::Reduce(fe, testing::KeepColumns(fe.basis, testing::ElasticColumns(fe.basis)));
  data.name = "box";
  const sid::ContactSurface bottom = data.surfaces.at(0);
  const Eigen::Index modes = data.num_modes();
  auto scene = std::make_unique<BoxOnPlane>();
  const int box = scene->system.AddBody(std::make_unique<FlexibleBody>("box", std::move(data), false));
  const MarkerRef origin = MarkerRef::OnBody(box, scene->system.body(box).FindMarker(FlexibleBody::kOriginMarker));
  scene->system.AddForceElement(floor(origin, bottom, modes));
  scene->y = scene->system.NeutralState();
  const Eigen::Vector3d centre(kA / 2, kB / 2, kC / 2);
  double lowest = HUGE_VAL;  // the lowest vertex of the turned box, about its centre
  for (const Eigen::Index v : {0, 1}) {
    for (const Eigen::Index w : {0, 1}) {
      lowest = std::min(lowest, (R_WB * (Eigen::Vector3d(v * kA, w * kB, 0.0) - centre)).z());
    }
  }
  const Eigen::Vector3d p_WBo_W = Eigen::Vector3d(0, 0, 1e-3 - lowest) - R_WB * centre;
  const Eigen::Index x0 = scene->system.position_offset(box), u0 = scene->system.num_positions();
  scene->y.segment<3>(x0) = p_WBo_W;
  scene->y.segment<4>(x0 + 3) = EulerParametersFromRotation(R_WB);
  scene->y(u0 + scene->system.velocity_offset(box) + 2) = -speed;
  return scene;
}

/// The box on a compliant surface_plane_contact of `law`.
std::unique_ptr<BoxOnPlane> MakeBoxOnPlane(const Eigen::Matrix3d& R_WB, double speed, const contact::NormalLaw& law) {
  return MakeBox(R_WB, speed, [&](const MarkerRef& origin, const sid::ContactSurface& bottom, Eigen::Index modes) {
    return std::make_unique<SurfacePlaneContact>("floor", origin, bottom, modes,
                                                 MarkerRef::Ground(Eigen::Vector3d::Zero()), CompliantContactLaw{law, {}});
  });
}

ContactModeAdvice OnlyAdvice(const BoxOnPlane& scene) {
  const std::vector<ContactModeAdvice> advice = AdviseContactModes(scene.system, scene.y);
  EXPECT_EQ(advice.size(), 1u);
  return advice.empty() ? ContactModeAdvice{} : advice.front();
}

TEST(ContactModeAdvice, AFaceLandingFlatPutsItsVerticesSpringsInParallel) {
  // 15 vertices touch at once, under the centre of mass: m* = m, k_total = 15 k, t_c = pi sqrt(m / (15 k)).
  const double k = 1e8, v = 0.5;
  const ContactModeAdvice flat = OnlyAdvice(*MakeBoxOnPlane(Eigen::Matrix3d::Identity(), v, contact::LinearLaw(k, 0.0)));
  EXPECT_EQ(flat.type, "surface_plane_contact");
  EXPECT_EQ(flat.body, "box");
  EXPECT_EQ(flat.first_points, 15);
  EXPECT_NEAR(flat.impact_speed, v, 1e-15);
  EXPECT_NEAR(flat.effective_mass / BoxMass(), 1.0, 1e-14);  // the FE mass is exact for hex8 (measured 1.0e-15)
  const double t_c = std::numbers::pi * std::sqrt(BoxMass() / (15.0 * k));
  EXPECT_NEAR(flat.contact_time / t_c, 1.0, 5e-15);  // measured 5.6e-16
  EXPECT_NEAR(flat.cutoff_hz * t_c, kCutoffTimesContactTimeWithout, 1e-13);
  EXPECT_FALSE(flat.correction_mode);
  // A uniform load on the bottom face loads the modes symmetric about both mid-planes only.
  EXPECT_GE(flat.loaded_modes, 1);
  EXPECT_LT(flat.loaded_modes, static_cast<int>(Box().basis.num_modes()) - 6);
  EXPECT_LE(flat.loaded_modes_above, flat.loaded_modes);

  // Four times stiffer: half the time, twice the cut-off; the linear law's t_c ignores the speed.
  const ContactModeAdvice stiffer =
      OnlyAdvice(*MakeBoxOnPlane(Eigen::Matrix3d::Identity(), 3 * v, contact::LinearLaw(4 * k, 0.0)));
  EXPECT_NEAR(stiffer.contact_time / flat.contact_time, 0.5, 1e-14);
  EXPECT_NEAR(stiffer.cutoff_hz / flat.cutoff_hz, 2.0, 1e-14);
}

TEST(ContactModeAdvice, AHertzLawsContactTimeFallsAsTheFifthRootOfTheSpeed) {
  const double k = 1e10;
  const ContactModeAdvice slow = OnlyAdvice(*MakeBoxOnPlane(Eigen::Matrix3d::Identity(), 0.1, contact::HertzLaw(k)));
  const ContactModeAdvice fast = OnlyAdvice(*MakeBoxOnPlane(Eigen::Matrix3d::Identity(), 3.2, contact::HertzLaw(k)));
  EXPECT_NEAR(fast.contact_time / slow.contact_time, 0.5, 1e-14);  // (32)^(-1/5); measured 1.1e-16
  // Johnson's t_c with the exact factor, k_total = 15 k.
  const double v = 0.1, m = BoxMass();
  EXPECT_NEAR(slow.contact_time / (2.943275184324214 * std::pow(5.0 * m * v * v / (4.0 * 15.0 * k), 0.4) / v), 1.0,
              2e-12);  // measured 1.7e-13 (SciPy's digits)
}

TEST(ContactModeAdvice, ATiltedBoxTouchesAtOneCornerWithItsEccentricEffectiveMass) {
  // Turned 0.1 rad about x and 0.2 about y: one corner first. The rigid box's effective mass there
  // along the ground's normal: 1/m* = 1/m + (r x n)^T I^-1 (r x n), I = m/12 diag(b^2 + c^2, a^2 +
  // c^2, a^2 + b^2) about the centre, r from the centre to the corner (Goldsmith 1960, ch. 4).
  const Eigen::Matrix3d R_WB =
      (Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY())).matrix();
  const double k = 1e8, v = 0.5;
  const ContactModeAdvice corner = OnlyAdvice(*MakeBoxOnPlane(R_WB, v, contact::LinearLaw(k, 0.0)));
  EXPECT_EQ(corner.first_points, 1);
  const double m = BoxMass();
  const Eigen::Vector3d I_B = m / 12.0 * Eigen::Vector3d(kB * kB + kC * kC, kA * kA + kC * kC, kA * kA + kB * kB);
  double inverse = HUGE_VAL;  // the lowest corner's
  double lowest = HUGE_VAL;
  for (const double x : {-kA / 2, kA / 2}) {
    for (const double yy : {-kB / 2, kB / 2}) {
      const Eigen::Vector3d r_B(x, yy, -kC / 2);
      if ((R_WB * r_B).z() >= lowest) continue;
      lowest = (R_WB * r_B).z();
      const Eigen::Vector3d lever = r_B.cross(R_WB.transpose() * Eigen::Vector3d::UnitZ());
      inverse = 1.0 / m + lever.cwiseProduct(lever).cwiseQuotient(I_B).sum();
    }
  }
  EXPECT_NEAR(corner.effective_mass * inverse, 1.0, 1e-14);  // measured 8.9e-16 (m* = 0.22 m)
  EXPECT_LT(corner.effective_mass, 0.5 * m);
  EXPECT_NEAR(corner.contact_time / (std::numbers::pi * std::sqrt(1.0 / (inverse * k))), 1.0, 1e-14);
}

TEST(ContactModeAdvice, PairsApartAndAtRestGetNone) {
  const std::unique_ptr<BoxOnPlane> scene = MakeBoxOnPlane(Eigen::Matrix3d::Identity(), 0.0, contact::LinearLaw(1e8, 0.0));
  EXPECT_TRUE(AdviseContactModes(scene->system, scene->y).empty());
}

// --- a pcm_contact: the box's bottom surface on a rigid flat ---------------------------------------

const contact::ElasticLayer kLayer{1e8, 2e-3};  // both sides: c = 1 / (2 h / E) = 2.5e10 N/m^3
constexpr double kLayerStiffness = 2.5e10;

/// The box's bottom (A, its SID surface as a modal side) pressing into the rigid square [-1, 1]^2
/// of the ground plane z = 0 (B, two triangles, normal +z).
std::unique_ptr<BoxOnPlane> MakeBoxOnFlat(const Eigen::Matrix3d& R_WB, double speed) {
  return MakeBox(R_WB, speed, [](const MarkerRef& origin, const sid::ContactSurface& bottom, Eigen::Index modes) {
    contact::PolygonMesh flat{Eigen::Matrix3Xd(3, 4), {3, 3}, {0, 1, 2, 0, 2, 3}};
    flat.vertices_W << -1, 1, 1, -1, -1, -1, 1, 1, 0, 0, 0, 0;
    return std::make_unique<PcmContactForce>(
        "floor", ModalPcmSurface(origin, bottom, modes, kLayer, false),
        PcmSurface{"flat", MarkerRef::Ground(Eigen::Vector3d::Zero()), flat, kLayer, false}, 0.0,
        contact::RegularisedCoulomb{0.0, 1e-3}, 0.01);
  });
}

TEST(ContactModeAdvice, APcmFaceLandingFlatIsALinearSpringOfTheLayersOverItsArea) {
  // Faces flat on each other: F = c A delta (n = 1, k = c a b), t_c = pi sqrt(m / (c a b)).
  const double v = 0.5;
  const ContactModeAdvice flat = OnlyAdvice(*MakeBoxOnFlat(Eigen::Matrix3d::Identity(), v));
  std::printf("[ numbers  ] PCM face on face: %s\n", flat.Describe().c_str());
  EXPECT_EQ(flat.type, "pcm_contact");
  EXPECT_EQ(flat.body, "box");
  EXPECT_NEAR(flat.impact_speed, v, 1e-12);
  EXPECT_NEAR(flat.effective_mass / BoxMass(), 1.0, 1e-14);  // measured -8.9e-16
  // Measured: n 1 (the fit's clamp at 1 holds a log2 a hair below), k 1.9e-11, t_c -9.3e-12: the
  // first touch is bisected to 1e-15 of the meshes' extent, a depth of 1e-4 of it.
  EXPECT_NEAR(flat.law_exponent, 1.0, 1e-10);
  EXPECT_NEAR(flat.law_stiffness / (kLayerStiffness * kA * kB), 1.0, 2e-10);
  const double t_c = std::numbers::pi * std::sqrt(BoxMass() / (kLayerStiffness * kA * kB));
  std::printf("[ numbers  ] against the closed form: n - 1 %.2e, k %.2e, m* %.2e, t_c %.2e\n", flat.law_exponent - 1.0,
              flat.law_stiffness / (kLayerStiffness * kA * kB) - 1.0, flat.effective_mass / BoxMass() - 1.0,
              flat.contact_time / t_c - 1.0);
  EXPECT_NEAR(flat.contact_time / t_c, 1.0, 1e-10);
  EXPECT_NEAR(flat.cutoff_hz * flat.contact_time, kCutoffTimesContactTimeWithout, 1e-12);
  // The same uniform load as the 15 vertex springs of surface_plane_contact, spread by the
  // triangles' weights: at least the modes those load.
  const ContactModeAdvice springs =
      OnlyAdvice(*MakeBoxOnPlane(Eigen::Matrix3d::Identity(), v, contact::LinearLaw(1e8, 0.0)));
  EXPECT_GE(flat.loaded_modes, springs.loaded_modes);
  EXPECT_LT(flat.loaded_modes, static_cast<int>(Box().basis.num_modes()) - 6);
}

TEST(ContactModeAdvice, APcmCornerPressingIntoAFlatIsACubicSpring) {
  // Turned 0.1 rad about x and 0.2 about y: the bottom face's lowest corner first. The face rises
  // from it at rates a1, a2 (m per m) along its two edges, so at a depth delta the part under the
  // flat is the triangle a1 s + a2 t <= delta, delta - a1 s - a2 t deep, seen by B's plane at the
  // face's |n_z|: V = |n_z| delta^3 / (6 a1 a2), F = c V (n = 3).
  const Eigen::Matrix3d R_WB =
      (Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY())).matrix();
  const double v = 0.5;
  const ContactModeAdvice corner = OnlyAdvice(*MakeBoxOnFlat(R_WB, v));
  std::printf("[ numbers  ] PCM corner on a face: %s\n", corner.Describe().c_str());
  double lowest = HUGE_VAL, a1 = 0.0, a2 = 0.0, inverse = 0.0;
  const double m = BoxMass();
  const Eigen::Vector3d I_B = m / 12.0 * Eigen::Vector3d(kB * kB + kC * kC, kA * kA + kC * kC, kA * kA + kB * kB);
  for (const double x : {-kA / 2, kA / 2}) {
    for (const double yy : {-kB / 2, kB / 2}) {
      const Eigen::Vector3d r_B(x, yy, -kC / 2);
      if ((R_WB * r_B).z() >= lowest) continue;
      lowest = (R_WB * r_B).z();
      a1 = (R_WB * Eigen::Vector3d(x > 0 ? -1.0 : 1.0, 0, 0)).z();
      a2 = (R_WB * Eigen::Vector3d(0, yy > 0 ? -1.0 : 1.0, 0)).z();
      const Eigen::Vector3d lever = r_B.cross(R_WB.transpose() * Eigen::Vector3d::UnitZ());
      inverse = 1.0 / m + lever.cwiseProduct(lever).cwiseQuotient(I_B).sum();
    }
  }
  const double n_z = std::abs((R_WB * Eigen::Vector3d::UnitZ()).z());
  const double k = kLayerStiffness * n_z / (6.0 * a1 * a2);
  std::printf("[ numbers  ] against the closed form: n - 3 %.2e, k %.2e, m* %.2e, t_c %.2e\n", corner.law_exponent - 3.0,
              corner.law_stiffness / k - 1.0, corner.effective_mass * inverse - 1.0,
              corner.contact_time / PowerLawContactTime(1.0 / inverse, v, k, 3.0) - 1.0);
  // Measured: n -6.0e-12, k -3.4e-11, t_c -1.1e-12; m* 1.1e-13 (the touch point is the first
  // elements' pressure centre, a hair from the corner).
  EXPECT_NEAR(corner.law_exponent, 3.0, 6e-11);
  EXPECT_NEAR(corner.law_stiffness / k, 1.0, 4e-10);
  EXPECT_NEAR(corner.effective_mass * inverse, 1.0, 1e-12);
  EXPECT_NEAR(corner.contact_time / PowerLawContactTime(1.0 / inverse, v, k, 3.0), 1.0, 1e-11);
}

// --- the PCM probe on rigid edges -------------------------------------------------------------------

/// A roof of length 2 along x: its ridge on the x axis, its two faces (two triangles each) rising
/// at 45 degrees to y = +-w, z = up * w (up = -1: pointing up), each counter-clockwise seen
/// along its outward normal (0, +-1, -up) / sqrt(2).
contact::PolygonMesh Roof(double w, double up) {
  contact::PolygonMesh roof{Eigen::Matrix3Xd(3, 6), {3, 3, 3, 3}, {}};
  roof.vertices_W << -1, 1, -1, 1, -1, 1, 0, 0, w, w, -w, -w, 0, 0, up * w, up * w, up * w, up * w;
  for (const std::array<int, 3>& t : std::vector<std::array<int, 3>>{{0, 1, 3}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}}) {
    const Eigen::Vector3d a = roof.vertices_W.col(t[0]), b = roof.vertices_W.col(t[1]), c = roof.vertices_W.col(t[2]);
    const Eigen::Vector3d outward(0.0, roof.vertices_W(1, t[2]) > 0 ? 1.0 : -1.0, -up);
    const bool ccw = (b - a).cross(c - a).dot(outward) > 0.0;
    for (const int v : ccw ? t : std::array<int, 3>{t[0], t[2], t[1]}) roof.face_vertices.push_back(v);
  }
  return roof;
}

/// The probe of a rigid roof (A, ridge down along x, on a free body 1 mm above the origin, falling
/// at 1 m/s) into `below` (B, on the ground), layers kLayer.
double ProbeForce(const contact::PolygonMesh& below, double depth, double* gap) {
  MultibodySystem system(Eigen::Vector3d::Zero());
  const int body = system.AddBody(std::make_unique<RigidBody>(
      "roof", 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity().eval(),
      std::vector<RigidBodyMarker>{{"ridge", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  system.AddForceElement(std::make_unique<PcmContactForce>(
      "edges", PcmSurface{"roof", MarkerRef::OnBody(body, 0), Roof(0.1, 1.0), kLayer, false},
      PcmSurface{"below", MarkerRef::Ground(Eigen::Vector3d::Zero()), below, kLayer, false}, 0.0,
      contact::RegularisedCoulomb{0.0, 1e-3}, 0.05));
  Eigen::VectorXd y = system.NeutralState(), x(7), u = Eigen::VectorXd::Zero(6);
  x << 0, 0, 1e-3, 1, 0, 0, 0;
  u(2) = -1.0;
  system.SetBodyState(body, x, u, y);
  const PcmTouchProbe probe(system, dynamic_cast<const PcmContactForce&>(system.force_element(0)), y);
  EXPECT_TRUE(probe.found());
  EXPECT_NEAR(probe.normal_W().z(), 1.0, 1e-12);
  EXPECT_NEAR(probe.gap_rate(), -1.0, 1e-12);
  *gap = probe.gap();
  return probe.At(depth).force;
}

TEST(ContactModeAdvice, ThePcmProbeGivesTheLayersForceOfAnEdgeOnAFaceAndOfAnEdgeAcrossAnEdge) {
  const double depth = 1e-3;
  double gap = 0.0;
  // An edge of length L = 2 on a flat: each face's wedge under the flat holds delta^2 / sqrt(2)
  // along its slope, seen at |n_z| = 1 / sqrt(2) by the flat: V = L delta^2, the overlap's own.
  contact::PolygonMesh flat{Eigen::Matrix3Xd(3, 4), {3, 3}, {0, 1, 2, 0, 2, 3}};
  flat.vertices_W << -2, 2, 2, -2, -2, -2, 2, 2, 0, 0, 0, 0;
  const double on_face = ProbeForce(flat, depth, &gap) / (kLayerStiffness * 2.0 * depth * depth);
  EXPECT_NEAR(gap, 1e-3, 1e-15);
  // Across a second roof, ridge up along y: each of the four face pairs holds delta^3 / 3 (A's face
  // under B's face's plane, within B's face's prism), V = 4 delta^3 / 3: twice the two roofs'
  // overlap |x| + |y| <= delta, 2 delta^3 / 3, as each point of A under both of B's faces counts
  // under each (the element is one-sided; docs/contact.md).
  contact::PolygonMesh across = Roof(0.2, -1.0);
  across.vertices_W.row(0).swap(across.vertices_W.row(1));  // the ridge along y
  for (std::size_t f = 0; f < across.face_vertices.size(); f += 3) std::swap(across.face_vertices[f + 1], across.face_vertices[f + 2]);
  const double on_edge = ProbeForce(across, depth, &gap) / (kLayerStiffness * 4.0 / 3.0 * std::pow(depth, 3));
  std::printf("[ numbers  ] edge on a face: c V / (c L delta^2) - 1 = %.2e; edge across an edge: c V / (4/3 c delta^3) "
              "- 1 = %.2e\n", on_face - 1.0, on_edge - 1.0);
  EXPECT_NEAR(on_face, 1.0, 2e-12);  // measured 1.4e-13
  EXPECT_NEAR(on_edge, 1.0, 2e-11);  // measured 1.6e-12
}

// --- a unilateral surface_plane on a free bar -------------------------------------------------------

constexpr double kLength = 0.5, kSide = 0.05;  // [m]

fem::IsotropicMaterial SteelWithoutPoisson() {
  fem::IsotropicMaterial steel = flexmbs::testing::Steel();
  steel.poisson_ratio = 0.0;
  return steel;
}

double WaveSpeed() { return std::sqrt(SteelWithoutPoisson().youngs_modulus_pa / SteelWithoutPoisson().density_kg_m3); }

TEST(ContactModeAdvice, ARigidContactOnABarTakesTheBarsOwnContactTime) {
  // A free bar (nu = 0: its axial motion a 1-D bar's) striking a wall with its end face: the
  // contact lasts 2L/c (Graff 1975, §1.2), the period of its lowest axial mode c / (2L); the
  // loaded modes are the axial ones, k c / (2L).
  const FeReducedBody fe = testing::FreeFreeBox(
      Eigen::Vector3i(50, 1, 1), Eigen::Vector3d(kLength, kSide, kSide), SteelWithoutPoisson(),
      [](const fem::Mesh& mesh) {
        return std::map<std::string, std::vector<int>>{{"end", flexmbs::testing::NodesOnPlane(mesh, 0, 0.0)}};
      },
      {"end"}, 8.5 * WaveSpeed() / (2.0 * kLength));
  const reduction::ReducedBasis basis = testing::KeepColumns(fe.basis, testing::ElasticColumns(fe.basis));
  sid::ReducedBody data = testing::Reduce(fe, basis);
  data.name = "bar";
  const sid::ContactSurface end = data.surfaces.at(0);
  const Eigen::Index modes = data.num_modes();
  MultibodySystem system(Eigen::Vector3d::Zero());
  const int bar = system.AddBody(std::make_unique<FlexibleBody>("bar", std::move(data), false));
  const MarkerRef origin = MarkerRef::OnBody(bar, system.body(bar).FindMarker(FlexibleBody::kOriginMarker));
  Eigen::Matrix3d R_WP;  // the wall's z axis along +x, at x = -1 mm
  R_WP << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  system.AddUnilateralContact(std::make_unique<SurfacePlaneUnilateral>(
      "wall", origin, end, modes, MarkerRef::Ground(Eigen::Vector3d(-1e-3, 0, 0), R_WP), UnilateralLaw{}));
  Eigen::VectorXd y = system.NeutralState();
  y(system.num_positions() + system.velocity_offset(bar)) = -1.0;
  const std::vector<ContactModeAdvice> advice = AdviseContactModes(system, y);
  ASSERT_EQ(advice.size(), 1u);
  const ContactModeAdvice& a = advice.front();
  EXPECT_TRUE(a.unilateral);
  EXPECT_EQ(a.type, "surface_plane");
  EXPECT_EQ(a.first_points, 4);
  const double two_l_over_c = 2.0 * kLength / WaveSpeed();
  EXPECT_NEAR(a.contact_time / two_l_over_c - 1.0, 0.0, 1e-3);  // 50 cells' dispersion: measured -1.6e-4
  EXPECT_NEAR(a.cutoff_hz * a.contact_time, kCutoffTimesContactTimeUnilateral, 1e-12);
  ASSERT_EQ(a.loaded_modes, 8);  // the axial modes below 8.5 c / (2L)
  for (int j = 0; j < a.loaded_modes; ++j) {
    const double f = basis.frequency_hz(a.loaded.at(static_cast<std::size_t>(j)));
    // The FE model's dispersion: measured 1.645e-4 (j + 1)^2 (1.06e-2 for the 8th).
    EXPECT_NEAR(f * two_l_over_c / (j + 1), 1.0, 3e-4 * (j + 1) * (j + 1)) << j;
  }
  EXPECT_EQ(a.loaded_modes_above, 4);  // above 4.5 c / (2L): the fifth to the eighth
}

}  // namespace
}  // namespace flexmbs::mbs
