// mbs/pcm_contact_force.h on reduced bodies' surfaces (mbs/pcm_surface.h): two clamped steel beams
// crossing at right angles and pressed into each other carry the force of the two beams and the
// layers in series (Euler-Bernoulli's 192 E I / L^3 per beam), equal and opposite on both, and
// deflect as their FE model does under the contact's nodal loads (K u = f solved here); the
// Jacobian with its modal columns against central differences; the scene entry with body sides and
// its one-line errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <array>
#include <random>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "sid/sid_file.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/input_error.h"
#include "tests/mbs/force_jacobian_differences.h"
#include "tests/mbs/pcm_flexible_bodies.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::ClampedBox;

constexpr double kLength = 0.4, kWidth = 0.02, kCell = 0.005;  // beams 0.4 x 0.02 x 0.02 m, 80 x 2 x 2 hex8
const contact::ElasticLayer kLayer{1e8, 2e-3};                   // c = 1 / (2 h / E) = 2.5e10 N/m^3 for two
constexpr double kMaxDepth = 2e-3;                               // [m]

/// A beam clamped at both end faces with the contact surface `surface` on its face z = z_face and
/// the attachment modes of that face's nodes within a cell of the crossing (x = L/2 +- w/2).
ClampedBox Beam(const std::string& name, const std::string& surface, double z_face) {
  const double half = 0.5 * kWidth + kCell;
  return testing::MakeClampedBox(
      name, Eigen::Vector3i(80, 2, 2), Vector3d(kLength, kWidth, kWidth),
      [](const fem::Mesh& mesh) {
        std::vector<int> ends = flexmbs::testing::NodesOnPlane(mesh, 0, 0.0);
        for (int node : flexmbs::testing::NodesOnPlane(mesh, 0, kLength)) ends.push_back(node);
        return ends;
      },
      surface, [z_face](const fem::Mesh& mesh) { return flexmbs::testing::NodesOnPlane(mesh, 2, z_face); },
      [=](const fem::Mesh& mesh) {
        return testing::NodesInBox(mesh, Vector3d(0.5 * kLength - half, 0.0, z_face),
                                   Vector3d(0.5 * kLength + half, kWidth, z_face));
      },
      4);
}
const ClampedBox& LowerBeam() {
  static const ClampedBox beam = Beam("lower", "top", kWidth);
  return beam;
}
const ClampedBox& UpperBeam() {
  static const ClampedBox beam = Beam("upper", "bottom", 0.0);
  return beam;
}

/// The two beams crossing: the lower along x from the origin, its top face z = w; the upper along
/// y (turned a quarter about z), its bottom face at z = w - interference, its width across the
/// lower's mid-span shifted by a fraction of a cell (no edges level with the lower's). The upper's
/// bottom face (A) presses into the lower's top face (B).
struct Crossing {
  Crossing(double interference, double areal_damping, const contact::RegularisedCoulomb& friction) {
    lower = system.AddBody(std::make_unique<FlexibleBody>("lower", LowerBeam().fe.body, false));
    upper = system.AddBody(std::make_unique<FlexibleBody>("upper", UpperBeam().fe.body, false));
    const auto side = [&](int b) {
      const auto& body = dynamic_cast<const FlexibleBody&>(system.body(b));
      return ModalPcmSurface(MarkerRef::OnBody(b, body.FindMarker(FlexibleBody::kOriginMarker)), body.data().surfaces.at(0),
                             body.num_modes(), kLayer, false);
    };
    law = contact::MakeElasticFoundation(kLayer, "A", kLayer, "B", areal_damping, friction);
    auto element = std::make_unique<PcmContactForce>("cross", side(upper), side(lower), areal_damping, friction, kMaxDepth);
    cross = element.get();
    system.AddForceElement(std::move(element));
    R_WU = Eigen::AngleAxisd(0.5 * M_PI, Vector3d::UnitZ()).toRotationMatrix();
    p_WUo_W = Vector3d(0.5 * kLength + 0.5 * kWidth + 1.3e-3, 0.5 * kWidth - 0.5 * kLength + 0.7e-3, kWidth - interference);
    y = system.NeutralState();
    VectorXd x(7 + system.body(upper).num_modes());
    x.setZero();
    const Eigen::Quaterniond e(R_WU);
    x.head<7>() << p_WUo_W, e.w(), e.x(), e.y(), e.z();
    system.SetBodyState(upper, x, VectorXd::Zero(6 + system.body(upper).num_modes()), y);
  }
  /// The reference's view of body b's side at y.
  testing::ReferenceSide Side(int b) const {
    const ClampedBox& box = b == lower ? LowerBeam() : UpperBeam();
    const auto& body = dynamic_cast<const FlexibleBody&>(system.body(b));
    const sid::ContactSurface& surface = body.data().surfaces.at(0);
    const VectorXd x = system.BodyPositions(y, b);
    return {&box, &surface, ModalPcmSurface(MarkerRef::Ground(Vector3d::Zero()), surface, body.num_modes(), kLayer, false).mesh_M,
            x.head<3>(), Eigen::Quaterniond(x(3), x(4), x(5), x(6)).toRotationMatrix(), x.tail(body.num_modes())};
  }

  MultibodySystem system{Vector3d::Zero()};
  int lower = 0, upper = 0;
  const PcmContactForce* cross = nullptr;
  contact::ElasticFoundation law;
  Eigen::Matrix3d R_WU;
  Vector3d p_WUo_W;
  VectorXd y;
};

/// Body b's FE displacements (3 N, in B) from its modal coordinates at y: Phi q.
VectorXd ReducedDisplacements(const Crossing& c, int b, const ClampedBox& box) {
  return box.fe.basis.Phi * c.system.BodyPositions(c.y, b).tail(box.fe.basis.num_modes());
}

TEST(PcmFlexible, TwoCrossingBeamsPressedTogetherCarryTheForceOfTheBeamsAndLayersInSeries) {
  constexpr double kInterference = 5e-4;  // [m]
  Crossing c(kInterference, 0.0, contact::RegularisedCoulomb{0.0, 1e-3});
  std::vector<testing::Unknown> unknowns = testing::ModalCoordinates(c.system, c.lower);
  for (const testing::Unknown& u : testing::ModalCoordinates(c.system, c.upper)) unknowns.push_back(u);
  const int iterations =
      testing::SolveStatics(c.system, unknowns, VectorXd::Zero(static_cast<Index>(unknowns.size())), 1e-8, 1e-7, c.y);
  ASSERT_GE(iterations, 0) << "Newton did not converge";
  // The contact's loads on the two frames (the clamps take them): equal and opposite.
  VectorXd h = VectorXd::Zero(c.system.num_velocities());
  c.cross->AddForces(0.0, c.system, c.y, h);
  const Vector3d f_lower = h.segment<3>(c.system.velocity_offset(c.lower)), f_upper = h.segment<3>(c.system.velocity_offset(c.upper));
  const Vector3d p_lower = c.system.BodyPositions(c.y, c.lower).head<3>(), p_upper = c.p_WUo_W;
  // The rotation rows are moments in body components (w_WB_B): the lower beam's B is W.
  const Vector3d moment_W = h.segment<3>(c.system.velocity_offset(c.lower) + 3) + p_lower.cross(f_lower) +
                            c.R_WU * h.segment<3>(c.system.velocity_offset(c.upper) + 3) + p_upper.cross(f_upper);
  const double F = -f_lower.z();
  // Closed form: two clamped-clamped Euler-Bernoulli beams under a central load (k = 192 E I / L^3
  // each) and the layers on the w x w patch (c w^2) in series.
  const double E = flexmbs::testing::Steel().youngs_modulus_pa, I = std::pow(kWidth, 4) / 12.0;
  const double k_beam = 192.0 * E * I / std::pow(kLength, 3), k_layers = c.law.stiffness * kWidth * kWidth;
  const double closed_form = kInterference / (2.0 / k_beam + 1.0 / k_layers);
  // The FE models under the elements' nodal loads, solved here (K u = f, the clamps held).
  const std::array<VectorXd, 2> f = testing::ReferenceNodalLoads(c.Side(c.upper), c.Side(c.lower), c.law, kMaxDepth);
  const VectorXd u_upper = testing::ClampedStaticResponse(UpperBeam(), f[0]);
  const VectorXd u_lower = testing::ClampedStaticResponse(LowerBeam(), f[1]);
  const double fe_error = std::max((ReducedDisplacements(c, c.upper, UpperBeam()) - u_upper).cwiseAbs().maxCoeff() /
                                       u_upper.cwiseAbs().maxCoeff(),
                                   (ReducedDisplacements(c, c.lower, LowerBeam()) - u_lower).cwiseAbs().maxCoeff() /
                                       u_lower.cwiseAbs().maxCoeff());
  // The FE beam's own stiffness under the load: F over its largest deflection.
  const double k_fe = F / u_lower.cwiseAbs().maxCoeff();
  std::printf("[ numbers  ] %d Newton steps; F %.6g N, closed form %.6g N (%.3e); FE beam %.4g N/m, Euler-Bernoulli %.4g "
              "N/m (%.3e); reduced vs FE deflection %.3e; f_A + f_B %.2e N, moments %.2e N m; nodal loads %.6g N\n",
              iterations, F, closed_form, F / closed_form - 1.0, k_fe, k_beam, k_fe / k_beam - 1.0, fe_error,
              (f_lower + f_upper).norm(), moment_W.norm(), f[1].reshaped(3, f[1].size() / 3).row(2).sum());
  EXPECT_GT(F, 100.0);
  // The Newton solve evaluated the element hundreds of times: its trees were built once each and
  // refitted since (the beams' deflections stay far below a rebuild's degradation).
  EXPECT_EQ(c.cross->tree_builds(), 2);
  // Measured: f_A + f_B exactly 0, their moments about W 5.7e-14 N m (round-off).
  EXPECT_LT((f_lower + f_upper).norm(), 1e-14 * F);
  EXPECT_LT(moment_W.norm(), 1e-15 * F * kLength);
  // Measured +3.7 %: the hex8 beams (2 x 2 cells across) are 4.8 % stiffer than Euler-Bernoulli's
  // (shear locking; Timoshenko's shear term would make the theory 3 % softer still).
  EXPECT_NEAR(F / closed_form, 1.0, 0.1);
  // Measured 7.9e-13: the attachment modes hold every static response to loads on the patch.
  EXPECT_LT(fe_error, 1e-11);
}

/// The relative differences between the element's Jacobian and central differences of its forces
/// (steps 1e-7 in velocities and positions): in u all of dh/du; in x on the rows and columns of
/// the frames' translations alone, and of the translations and modal coordinates of both bodies
/// (the rotations' columns leave out the levers' turning, as every contact element's).
struct JacobianErrors {
  double u = 0.0, translations = 0.0, modes = 0.0;
};
JacobianErrors CompareJacobian(const MultibodySystem& system, const ForceElement& element, const VectorXd& y) {
  const Index n = system.num_velocities();
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(n, n), dh_du = dh_dx;
  element.AddForceJacobian(0.0, system, y, dh_dx, dh_du);
  constexpr double kStep = 1e-7;  // [m/s], [m]
  const flexmbs::testing::DifferenceJacobian fd = flexmbs::testing::ForceJacobianByDifferences(system, element, y, kStep);
  const Eigen::MatrixXd& fd_u = fd.dh_du;
  const Eigen::MatrixXd& fd_x = fd.dh_dx;
  std::vector<Index> translations, modes;
  for (int b = 0; b < system.num_bodies(); ++b) {
    for (Index k = 0; k < system.body(b).num_velocities(); ++k) {
      if (k < 3 || k >= 6) modes.push_back(system.velocity_offset(b) + k);
      if (k < 3) translations.push_back(system.velocity_offset(b) + k);
    }
  }
  const auto error = [&](const std::vector<Index>& kept) {
    return (dh_dx(kept, kept) - fd_x(kept, kept)).norm() / fd_x(kept, kept).norm();
  };
  return {(dh_du - fd_u).norm() / fd_u.norm(), error(translations), error(modes)};
}

/// Random velocities (frames and modes) and small random modal displacements (up to 2 um per
/// mode) on both beams.
void Stir(Crossing& c, std::mt19937& rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const int b : {c.lower, c.upper}) {
    VectorXd x = c.system.BodyPositions(c.y, b), u(c.system.body(b).num_velocities());
    for (Index k = 0; k < u.size(); ++k) u(k) = (k < 3 ? 0.01 : k < 6 ? 0.1 : 0.01) * uniform(rng);
    const ClampedBox& box = b == c.lower ? LowerBeam() : UpperBeam();
    for (Index k = 0; k < box.fe.basis.num_modes(); ++k) {
      x(7 + k) = 2e-6 * uniform(rng) / box.fe.basis.Phi.col(k).cwiseAbs().maxCoeff();
    }
    c.system.SetBodyState(b, x, u, c.y);
  }
}

// The modal rows take each element's force lumped at its pressure centre through the weights
// there. Moving one vertex along the normal shifts the pressure centres of its elements towards it
// by (element size)^2 / depth times the motion, which changes the weights at first order whatever
// the depth: the Jacobian takes the lumped load's consistent derivative, c integral(J_i^T d_F n^T
// J'_j dA) over each patch, from the patch's moments about the pressure centre and the weights'
// gradients. What it still holds (the normals' turning, the areas' change by in-plane motion, the
// damping's d_A v_N dA/dx) is of order depth / element size.
TEST(PcmFlexible, TheJacobianIsExactInVelocityAndConsistentInTheModesToTheDepthOverTheElementSize) {
  std::mt19937 rng(3);
  // Damping and friction at slips of the order of the regularisation speed.
  Crossing damped(5e-4, 2e5, contact::RegularisedCoulomb{0.4, 1e-2});
  Stir(damped, rng);
  const JacobianErrors full = CompareJacobian(damped.system, *damped.cross, damped.y);
  std::printf("[ numbers  ] damped, with friction: dh/du %.3e; dh/dx translations %.3e, with the modes %.3e\n", full.u,
              full.translations, full.modes);
  EXPECT_LT(full.u, 1e-7);  // measured 1.1e-8: round-off of the differences (h ~ 1e3 N, step 1e-7)
  EXPECT_LT(full.translations, 0.1);  // measured 2.9e-2: the damping's d_A v_N dA/dx left out
  EXPECT_LT(full.modes, 0.6);         // measured 0.35 (0.46 with the pressure centres held)
  std::array<double, 2> modes{};
  const std::array<double, 2> interferences{5e-4, 2e-5};
  for (std::size_t k = 0; k < 2; ++k) {
    Crossing elastic(interferences[k], 0.0, contact::RegularisedCoulomb{0.0, 1e-2});
    Stir(elastic, rng);
    const JacobianErrors errors = CompareJacobian(elastic.system, *elastic.cross, elastic.y);
    modes[k] = errors.modes;
    std::printf("[ numbers  ] undamped at %.0e m: dh/dx translations %.3e, with the modes %.3e\n", interferences[k],
                errors.translations, errors.modes);
    // Measured 4.7e-5 and 2.5e-5: on the deformed (no longer flat) faces the areas and normals
    // held (6e-12 with the modal coordinates at 0).
    EXPECT_LT(errors.translations, 5e-4);
  }
  // Measured 0.21 and 9.2e-3 (0.37 and 0.32 with the pressure centres held): first order in the
  // depth, 0.5 mm and 0.02 mm against cells of 5 x 10 mm.
  EXPECT_LT(modes[0], 0.5);
  EXPECT_LT(modes[1], 0.05);
  EXPECT_GT(modes[0] / modes[1], 10.0);
}

/// A scene folder with the two beams' body files and a scene of them (and a rigid block) whose
/// forces are `forces` (YAML list items).
class CrossingScene {
 public:
  CrossingScene() : dir_(std::filesystem::temp_directory_path() / ("flexmbs_pcm_scene_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    sid::WriteReducedBody(dir_ / "lower.sid.h5", LowerBeam().fe.body);
    sid::WriteReducedBody(dir_ / "upper.sid.h5", UpperBeam().fe.body);
  }
  ~CrossingScene() { std::filesystem::remove_all(dir_); }
  CrossingScene(const CrossingScene&) = delete;
  CrossingScene& operator=(const CrossingScene&) = delete;

  std::filesystem::path Write(const Vector3d& p_WUo_W, const std::string& forces) const {
    const std::filesystem::path file = dir_ / "scene.yaml";
    std::ofstream(file) << "gravity: [0, 0, 0]\nbodies:\n"
                        << "  lower: {flexible: {file: lower.sid.h5, geometric_stiffening: false}}\n"
                        << "  upper:\n    flexible: {file: upper.sid.h5, geometric_stiffening: false}\n"
                        << "    initial: {position: [" << p_WUo_W.x() << ", " << p_WUo_W.y() << ", " << p_WUo_W.z()
                        << "], rotation: {axis: [0, 0, 1], angle: 1.5707963267948966}}\n"
                        << "  block:\n    rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n"
                        << "    initial: {position: [0, 0, 1]}\n"
                        << "forces:\n" << forces << "simulation: {end_time: 1e-3}\n";
    return file;
  }

 private:
  std::filesystem::path dir_;
};

TEST(PcmFlexible, ASceneNamesABodysSurfaceAsASideAndBadSidesAreOneLineErrors) {
  const Crossing direct(5e-4, 0.0, contact::RegularisedCoulomb{0.0, 1e-3});
  const CrossingScene scene;
  const std::string layer = "layer: {modulus: 1e8, thickness: 2e-3}";
  const Scene loaded = LoadScene(scene.Write(direct.p_WUo_W, "  - name: cross\n    type: pcm_contact\n"
                                                             "    a: {body: upper, surface: bottom, " + layer + "}\n"
                                                             "    b: {body: lower, surface: top, " + layer + "}\n"
                                                             "    max_depth: 2e-3\n"));
  // The scene's element at the scene's state against the element built directly at that state.
  const MultibodySystem& system = *loaded.system;
  VectorXd y = direct.y;
  for (const int b : {direct.lower, direct.upper}) {
    direct.system.SetBodyState(b, system.BodyPositions(loaded.initial_state, b), system.BodyVelocities(loaded.initial_state, b), y);
  }
  VectorXd h_scene = VectorXd::Zero(system.num_velocities()), h_direct = VectorXd::Zero(direct.system.num_velocities());
  system.force_element(0).AddForces(0.0, system, loaded.initial_state, h_scene);
  direct.cross->AddForces(0.0, direct.system, y, h_direct);
  EXPECT_GT(h_direct.norm(), 100.0);
  EXPECT_EQ(h_scene.head(h_direct.size()), h_direct);
  EXPECT_TRUE(h_scene.tail(6).isZero()) << "the block takes nothing";

  const auto error = [&](const std::string& a) {
    return flexmbs::testing::InputErrorMessage([&] {
      LoadScene(scene.Write(direct.p_WUo_W, "  - name: cross\n    type: pcm_contact\n    a: " + a + "\n"
                                            "    b: {body: lower, surface: top, " + layer + "}\n    max_depth: 2e-3\n"));
    });
  };
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(error("{body: middle, surface: bottom, " + layer + "}"), "forces[0].a.body: force element 'cross': no body 'middle'");
  expect(error("{body: block, surface: bottom, " + layer + "}"),
         "forces[0].a.body: force element 'cross': body 'block' is rigid; surfaces are a flexible body's");
  expect(error("{body: upper, surface: side, " + layer + "}"),
         "forces[0].a.surface: force element 'cross': body 'upper' carries no contact surface 'side' (it has: bottom)");
  expect(error("{body: upper, surface: bottom, mesh: upper.stl, " + layer + "}"), "forces[0].a");
  expect(error("{body: upper, surface: bottom, layer: {modulus: 0, thickness: 2e-3}}"),
         "force element 'cross': layer modulus of surface 'bottom' 0 must be finite and > 0");
  // The bottom patch is open: closed: true finds its rim.
  expect(error("{body: upper, surface: bottom, closed: true, " + layer + "}"), "force element 'cross': surface 'bottom'");
}

}  // namespace
}  // namespace flexmbs::mbs
