#include "tests/validation/simeon_crank_model.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/centrifugal.h"
#include "core/error.h"
#include "core/skew.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/time_function.h"

namespace flexmbs::validation {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr int n = kRodModes;

// Outputs at this interval [s] unwrap the crank angle (0.15 rad apart at 150 rad/s).
constexpr double kOutputInterval = 1e-3;

const Matrix3d& Product(const RodIntegrals& r, int i, int j) {
  return r.product[static_cast<std::size_t>(i * n + j)];
}
Matrix3d& Product(RodIntegrals& r, int i, int j) {
  return r.product[static_cast<std::size_t>(i * n + j)];
}

// int a x b dm of the pair whose product is P = int a b^T dm.
Vector3d CrossOfProduct(const Matrix3d& P) {
  return Vector3d(P(1, 2) - P(2, 1), P(2, 0) - P(0, 2), P(0, 1) - P(1, 0));
}

// The section's part of the rigid inertia about Bo with crank.f's J2 about z (file comment):
// diag(m (BB^2 + HH^2) / 12, m (L^2 / 3 + BB^2 / 12), J2).
Matrix3d RodInertia(const SimeonCrankData& data, double mass, double length, double inertia_z) {
  return Vector3d(mass * (data.width * data.width + data.height * data.height) / 12.0,
                  mass * (length * length / 3.0 + data.width * data.width / 12.0), inertia_z)
      .asDiagonal();
}

// Per mode at xi: the axial strain u' (row 0) and the curvature v'' (row 1) [1/m per q].
Eigen::Matrix<double, 2, n> RodStrains(double xi, double length) {
  constexpr double pi = std::numbers::pi;
  Eigen::Matrix<double, 2, n> s = Eigen::Matrix<double, 2, n>::Zero();
  for (int k = 1; k <= 2; ++k) s(1, k - 1) = -std::pow(k * pi / length, 2) * std::sin(k * pi * xi);
  s(0, 2) = (4.0 - 8.0 * xi) / length;
  s(0, 3) = (4.0 * xi - 1.0) / length;
  return s;
}

// Gauss-Legendre nodes and weights on [0, 1] (Golub-Welsch: the eigenvalues of the Jacobi matrix
// of the Legendre polynomials, weights from the first components of its eigenvectors).
void GaussLegendre(int points, VectorXd* nodes, VectorXd* weights) {
  MatrixXd jacobi = MatrixXd::Zero(points, points);
  for (int k = 1; k < points; ++k) {
    jacobi(k - 1, k) = jacobi(k, k - 1) = k / std::sqrt(4.0 * k * k - 1.0);
  }
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eigen(jacobi);
  *nodes = 0.5 * (eigen.eigenvalues().array() + 1.0);
  *weights = eigen.eigenvectors().row(0).transpose().array().square();  // 2 v0^2 on [-1, 1], halved
}

// A SID node on the centreline at x = xi L: the modes' displacement there and their slope about
// B z (the lateral modes' dv/dx, with pi = data.pi).
sid::Node CentrelineNode(const std::string& name, int fe_node, double xi,
                         const Eigen::Matrix<double, 3, n>& Phi_K, const SimeonCrankData& data) {
  sid::Node node;
  node.name = name;
  node.fe_nodes = {fe_node};
  node.coupling = "node";
  node.origin.m0 = Vector3d(xi * data.rod_length, 0.0, 0.0);
  node.phi.m0 = Phi_K;
  node.psi.m0 = MatrixXd::Zero(3, n);
  for (int k = 1; k <= 2; ++k) {
    node.psi.m0(2, k - 1) = k * data.pi / data.rod_length * std::cos(k * data.pi * xi);
  }
  node.AP.m0 = Matrix3d::Identity();
  for (int j = 0; j < n; ++j) {
    node.origin.m1.emplace_back(Phi_K.col(j));
    node.AP.m1.emplace_back(Skew(node.psi.m0.col(j)));
  }
  return node;
}

// The rod's rigid data (mass, centre of mass at L/2, inertia), its modes' names and kinds, and
// the pinned rod's frequencies of the two sines (NaN for the axial constraint modes).
void SetRodRigidData(const RodIntegrals& r, sid::ReducedBody* body) {
  const double m = r.mass;
  const Vector3d c = 0.5 * r.length * Vector3d::UnitX();
  body->name = "rod";
  body->mass = m;
  body->center_of_mass = c;
  body->inertia_about_center_of_mass =
      r.inertia_Bo - m * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
  body->mode_names = {"lateral_1", "lateral_2", "axial_mid", "axial_end"};
  body->mode_kinds = {"normal", "normal", "constraint", "constraint"};
  body->frequency_hz = VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < 2; ++k) {  // the sines are the modes of the rod pinned at both ends
    body->frequency_hz(k) =
        std::sqrt(r.stiffness(k, k) / Product(r, k, k).trace()) / (2.0 * std::numbers::pi);
  }
  body->relative_residuals = VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  body->damping = "none";
}

// docs/sid.md's integrals of order 0 and 1 in q with r = x e1: int r dm = m c, int x Phi_j dm =
// s_j (and Ge's, Me's order 0 sized here for the order-2 terms).
void SetRodFirstOrderIntegrals(const RodIntegrals& r, sid::ReducedBody* body) {
  const Vector3d e1 = Vector3d::UnitX(), c = 0.5 * r.length * e1;
  const Matrix3d I3 = Matrix3d::Identity();
  const std::array<Matrix3d, 6>& W = CentrifugalBasis();
  body->mdCM.m0 = r.mass * c;
  body->J.m0 = r.inertia_Bo;
  body->Ct.m0 = MatrixXd::Zero(n, 3);
  body->Cr.m0 = MatrixXd::Zero(n, 3);
  body->Me.m0 = MatrixXd::Zero(n, n);
  body->Gr.m0 = MatrixXd::Zero(3, 3 * n);
  body->Ge.m0 = MatrixXd::Zero(n, 3 * n);
  body->Oe.m0 = MatrixXd::Zero(n, 6);
  for (int j = 0; j < n; ++j) {
    const Vector3d& s = r.moment[static_cast<std::size_t>(j)];
    body->mdCM.m1.emplace_back(r.first[static_cast<std::size_t>(j)]);
    // int (r~ Phi_j~^T + Phi_j~ r~^T) dm = 2 (r . Phi_j) I - Phi_j r^T - r Phi_j^T, integrated.
    body->J.m1.emplace_back(2.0 * s.x() * I3 - s * e1.transpose() - e1 * s.transpose());
    body->Ct.m0.row(j) = r.first[static_cast<std::size_t>(j)].transpose();
    body->Cr.m0.row(j) = e1.cross(s).transpose();  // int r x Phi_j dm
    // 2 int r~^T Phi_j~ dm = 2 ((r . Phi_j) I - Phi_j r^T), integrated.
    body->Gr.m0.middleCols<3>(3 * j) = 2.0 * (s.x() * I3 - s * e1.transpose());
    for (int l = 0; l < 6; ++l) {  // int Phi_j^T W_l r dm
      body->Oe.m0(j, l) = (W[static_cast<std::size_t>(l)] * e1).dot(s);
    }
  }
}

// The integrals of the modes' products int Phi_j Phi_k^T dm = P_jk: J's order 2, Me, Cr's and
// Gr's and Oe's order 1, Ge.
void SetRodProductIntegrals(const RodIntegrals& r, sid::ReducedBody* body) {
  const Matrix3d I3 = Matrix3d::Identity();
  const std::array<Matrix3d, 6>& W = CentrifugalBasis();
  body->Cr.m1.assign(n, MatrixXd::Zero(n, 3));
  body->Gr.m1.assign(n, MatrixXd::Zero(3, 3 * n));
  body->Oe.m1.assign(n, MatrixXd::Zero(n, 6));
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) {
      const Matrix3d& P = Product(r, j, k);
      // 1/2 int (Phi_j~ Phi_k~^T + Phi_k~ Phi_j~^T) dm
      //   = int (Phi_j . Phi_k) I - 1/2 (Phi_j Phi_k^T + Phi_k Phi_j^T) dm.
      body->J.m2.emplace_back(P.trace() * I3 - 0.5 * (P + Product(r, k, j)));
      body->Me.m0(j, k) = P.trace();
      // Row k of Cr's m1[j]: int Phi_j x Phi_k dm; of Ge's block j: twice that.
      body->Cr.m1[static_cast<std::size_t>(j)].row(k) = CrossOfProduct(P).transpose();
      body->Ge.m0.block<1, 3>(k, 3 * j) = 2.0 * CrossOfProduct(P).transpose();
      // block j of Gr's m1[k]: 2 int Phi_k~^T Phi_j~ dm = 2 ((Phi_k . Phi_j) I - Phi_j Phi_k^T).
      body->Gr.m1[static_cast<std::size_t>(k)].middleCols<3>(3 * j) = 2.0 * (P.trace() * I3 - P);
      for (int l = 0; l < 6; ++l) {
        body->Oe.m1[static_cast<std::size_t>(k)](j, l) =
            W[static_cast<std::size_t>(l)].cwiseProduct(P).sum();
      }
    }
  }
}

// The ends: A (Bo, where every mode vanishes) and B, which moves along B x by q4 alone.
void SetRodEnds(double length, const SimeonCrankData& data, sid::ReducedBody* body) {
  Eigen::Matrix<double, 3, n> Phi_tip = Eigen::Matrix<double, 3, n>::Zero();
  Phi_tip(0, 3) = 1.0;
  body->node_positions = Eigen::Matrix3Xd::Zero(3, 2);
  body->node_positions(0, 1) = length;
  body->phi = MatrixXd::Zero(6, n);
  body->phi.bottomRows<3>() = Phi_tip;
  body->node_sets = {{"root", {0}}, {"tip", {1}}};
  body->nodes = {CentrelineNode("root", 0, 0.0, Eigen::Matrix<double, 3, n>::Zero(), data),
                 CentrelineNode("tip", 1, 1.0, Phi_tip, data)};
}

}  // namespace

SimeonState SimeonInitialValues() {
  SimeonState y;
  y.segment<7>(0) << 0.0, 0.0, .450016933, 0.0, 0.0, .103339863e-04, .169327969e-04;
  y.segment<7>(7) << 150.0, -.749957670e+02, -.268938672e-05, .444896105, .463434311e-02,
      -.178591076e-05, -.268938672e-05;
  y.segment<7>(14) << 0.0, -1.344541576008661e-03, -5.062194923138079e+03, -6.833142732779555e-05,
      1.449382650173157e-08, -4.268463211410861, 2.098334687947376e-01;
  y.segment<3>(21) << -6.397251492537153e-08, 3.824589508329281e+02, -4.376060460948886e-09;
  return y;
}

Eigen::Matrix<double, 3, kRodModes> RodShapes(double xi) {
  constexpr double pi = std::numbers::pi;
  Eigen::Matrix<double, 3, n> Phi = Eigen::Matrix<double, 3, n>::Zero();
  Phi(1, 0) = std::sin(pi * xi);
  Phi(1, 1) = std::sin(2.0 * pi * xi);
  Phi(0, 2) = 4.0 * xi * (1.0 - xi);
  Phi(0, 3) = xi * (2.0 * xi - 1.0);
  return Phi;
}

RodIntegrals CrankRodIntegrals(const SimeonCrankData& data) {
  const double L = data.rod_length, p = data.pi;
  const double mL = data.density * data.width * data.height * L;  // crank.f's FACM
  RodIntegrals r;
  r.mass = data.rod_mass;
  r.length = L;
  r.inertia_Bo = RodInertia(data, data.rod_mass, L, data.rod_inertia);
  r.first = {Vector3d(0.0, 2.0 / p * mL, 0.0), Vector3d::Zero(), Vector3d(2.0 / 3.0 * mL, 0.0, 0.0),
             Vector3d(mL / 6.0, 0.0, 0.0)};
  r.moment = {Vector3d(0.0, mL * L / p, 0.0), Vector3d(0.0, -mL * L / (2.0 * p), 0.0),
              Vector3d(mL * L / 3.0, 0.0, 0.0), Vector3d(mL * L / 6.0, 0.0, 0.0)};
  for (Matrix3d& P : r.product) P.setZero();
  // int sin(j pi xi) sin(k pi xi) dxi = delta_jk / 2; int N_i N_j dxi = [8 1; 1 2] / 15.
  Product(r, 0, 0)(1, 1) = Product(r, 1, 1)(1, 1) = 0.5 * mL;
  const double axial[2][2] = {{8.0, 1.0}, {1.0, 2.0}};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      Product(r, 2 + i, 2 + j)(0, 0) = data.axial_mass_scale * axial[i][j] / 15.0 * mL;
    }
  }
  // int N_axial sin(k pi xi) dxi: the axial-lateral products (crank.f's BQ).
  const double cross[2][2] = {{16.0 / (p * p * p), 0.0}, {1.0 / p - 8.0 / (p * p * p), -0.5 / p}};
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 2; ++k) {
      Product(r, 2 + i, k)(0, 1) = cross[i][k] * mL;
      Product(r, k, 2 + i) = Product(r, 2 + i, k).transpose();
    }
  }
  const double EI = data.youngs_modulus * data.width * std::pow(data.height, 3) / 12.0;
  const double EA = data.youngs_modulus * data.width * data.height;
  for (int k = 1; k <= 2; ++k) r.stiffness(k - 1, k - 1) = EI * std::pow(k * p / L, 4) * L / 2.0;
  r.stiffness.bottomRightCorner<2, 2>() << 16.0 / 3.0, -8.0 / 3.0, -8.0 / 3.0, 7.0 / 3.0;
  r.stiffness.bottomRightCorner<2, 2>() *= EA / L;
  return r;
}

RodIntegrals QuadratureRodIntegrals(const SimeonCrankData& data, int points) {
  FLEXMBS_CHECK(points >= 2, "QuadratureRodIntegrals: at least 2 points");
  const double L = data.rod_length, mu = data.density * data.width * data.height;
  const double EI = data.youngs_modulus * data.width * std::pow(data.height, 3) / 12.0;
  const double EA = data.youngs_modulus * data.width * data.height;
  VectorXd xi, w;
  GaussLegendre(points, &xi, &w);
  RodIntegrals r;
  r.length = L;
  for (Vector3d& v : r.first) v.setZero();
  for (Vector3d& v : r.moment) v.setZero();
  for (Matrix3d& P : r.product) P.setZero();
  for (Index g = 0; g < xi.size(); ++g) {
    const double dm = mu * L * w(g), x = L * xi(g);
    const Eigen::Matrix<double, 3, n> Phi = RodShapes(xi(g));
    const Eigen::Matrix<double, 2, n> strain = RodStrains(xi(g), L);
    r.mass += dm;
    for (int i = 0; i < n; ++i) {
      r.first[static_cast<std::size_t>(i)] += dm * Phi.col(i);
      r.moment[static_cast<std::size_t>(i)] += dm * x * Phi.col(i);
      for (int j = 0; j < n; ++j) Product(r, i, j) += dm * Phi.col(i) * Phi.col(j).transpose();
    }
    r.stiffness += L * w(g) *
                   (EA * strain.row(0).transpose() * strain.row(0) +
                    EI * strain.row(1).transpose() * strain.row(1));
  }
  r.inertia_Bo =
      RodInertia(data, r.mass, L, r.mass * (L * L / 3.0 + data.height * data.height / 12.0));
  return r;
}

sid::ReducedBody RodBody(const RodIntegrals& r, const SimeonCrankData& data) {
  sid::ReducedBody body;
  SetRodRigidData(r, &body);
  SetRodFirstOrderIntegrals(r, &body);
  SetRodProductIntegrals(r, &body);
  body.Ke.m0 = r.stiffness;
  body.De.m0 = MatrixXd::Zero(n, n);
  body.ksigma.m0 = MatrixXd::Zero(n, 1);
  SetRodEnds(r.length, data, &body);
  body.provenance = {
      {"source", "IVP Test Set crank.f (B. Simeon): the rod's integrals in closed form"},
      {"built_by", "tests/validation/simeon_crank_model.cc"}};
  return body;
}

SimeonRun RunSimeonCrank(const SimeonCrankData& data, const sid::ReducedBody& rod_body,
                         const SimeonState& start, const mbs::OdeOptions& integrator,
                         double end_time) {
  mbs::MultibodySystem system(Vector3d::Zero());
  const Matrix3d I3 = Matrix3d::Identity();
  const Vector3d x = Vector3d::UnitX(), z = Vector3d::UnitZ();
  const double L1 = data.crank_length;
  // The crank: J1 about the pivot, its centre of mass at L1 / 2 (the driver prescribes its motion).
  const double crank_cm_inertia = data.crank_inertia - data.crank_mass * 0.25 * L1 * L1;
  const int crank = system.AddBody(std::make_unique<mbs::RigidBody>(
      "crank", data.crank_mass, 0.5 * L1 * x,
      Vector3d(1e-3 * crank_cm_inertia, crank_cm_inertia, crank_cm_inertia).asDiagonal(),
      std::vector<mbs::RigidBodyMarker>{{"pivot", Vector3d::Zero(), I3}, {"pin", L1 * x, I3}}));
  const int rod = system.AddBody(std::make_unique<mbs::FlexibleBody>("rod", rod_body, false));
  // The slider: a point mass; its marker "guide" turns z onto B x (the prismatic joint's axis).
  const Matrix3d R_guide =
      Eigen::AngleAxisd(0.5 * std::numbers::pi, Vector3d::UnitY()).toRotationMatrix();
  const double slider_inertia = 1e-6;  // [kg m^2], locked by the prismatic joint
  const int slider = system.AddBody(std::make_unique<mbs::RigidBody>(
      "slider", data.slider_mass, Vector3d::Zero(), slider_inertia * I3,
      std::vector<mbs::RigidBodyMarker>{{"pin", Vector3d::Zero(), I3},
                                        {"guide", Vector3d::Zero(), R_guide}}));
  const int drive = system.AddJoint(
      mbs::Joint("crank_drive", mbs::JointType::kRevolute, mbs::MarkerRef::Ground(Vector3d::Zero()),
                 system.Marker("crank", "pivot"), mbs::MakeRamp(0.0, data.spin)));
  system.AddJoint(mbs::Joint("crank_rod", mbs::JointType::kRevolute, system.Marker("crank", "pin"),
                             system.Marker("rod", "root")));
  const int wrist =
      system.AddJoint(mbs::Joint("rod_slider", mbs::JointType::kRevolute,
                                 system.Marker("rod", "tip"), system.Marker("slider", "pin")));
  system.AddJoint(mbs::Joint("slider_guide", mbs::JointType::kPrismatic,
                             mbs::MarkerRef::Ground(Vector3d::Zero(), R_guide),
                             system.Marker("slider", "guide")));

  // Simeon's positions and velocities: the crank and the rod turned about W z, the rod's frame at
  // the crank's tip A (velocity L1 phi1' along the crank's normal), the slider at x3.
  const double phi1 = start(0), phi2 = start(1), w1 = start(7), w2 = start(8);
  const Eigen::Vector4d e_crank(std::cos(0.5 * phi1), 0.0, 0.0, std::sin(0.5 * phi1));
  const Eigen::Vector4d e_rod(std::cos(0.5 * phi2), 0.0, 0.0, std::sin(0.5 * phi2));
  Eigen::VectorXd y0 = system.NeutralState();
  Eigen::Matrix<double, 7, 1> x_crank;
  x_crank << Vector3d::Zero(), e_crank;
  Eigen::Matrix<double, 6, 1> u_crank;
  u_crank << Vector3d::Zero(), w1 * z;
  system.SetBodyState(crank, x_crank, u_crank, y0);
  VectorXd x_rod(7 + n), u_rod(6 + n);
  x_rod << L1 * Vector3d(std::cos(phi1), std::sin(phi1), 0.0), e_rod, start.segment<n>(3);
  u_rod << L1 * w1 * Vector3d(-std::sin(phi1), std::cos(phi1), 0.0), w2 * z, start.segment<n>(10);
  system.SetBodyState(rod, x_rod, u_rod, y0);
  Eigen::Matrix<double, 7, 1> x_slider;
  x_slider << start(2) * x, 1.0, 0.0, 0.0, 0.0;
  Eigen::Matrix<double, 6, 1> u_slider;
  u_slider << start(9) * x, Vector3d::Zero();
  system.SetBodyState(slider, x_slider, u_slider, y0);

  mbs::SimulationOptions options;
  options.integrator = integrator;
  options.end_time = end_time;
  options.output_interval = kOutputInterval;

  const auto angle_about_z = [](const Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); };
  double crank_angle = phi1, last_time = 0.0;
  Eigen::VectorXd last_y, first_y;
  const auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
    if (first_y.size() == 0) first_y = y;
    const double wrapped =
        angle_about_z(system.MarkerState(system.Marker("crank", "pivot"), y).R_WM);
    crank_angle += std::remainder(wrapped - crank_angle, 2.0 * std::numbers::pi);
    last_time = t;
    last_y = y;
  };
  const mbs::SimulationStatistics statistics = mbs::Simulate(system, options, y0, record);

  SimeonRun run;
  run.projected_position = (first_y - y0).head(system.num_positions()).cwiseAbs().maxCoeff();
  run.dropped_rows =
      static_cast<long>(statistics.initial_conditions.redundancy.dropped_rows.size());
  run.steps = statistics.integrator.steps;
  run.wall_seconds = statistics.wall_seconds;

  VectorXd u_dot(system.num_velocities()), lambda(system.num_constraints());
  system.Accelerations(last_time, last_y, u_dot, lambda);
  const auto x_of = [&](int b) { return system.BodyPositions(last_y, b); };
  const auto u_of = [&](int b) { return system.BodyVelocities(last_y, b); };
  const auto u_dot_of = [&](int b) {
    return u_dot.segment(system.velocity_offset(b), system.body(b).num_velocities());
  };
  const mbs::JointLoad on_slider = system.ConstraintLoad(wrist, last_time, last_y, lambda);
  const mbs::JointLoad on_crank = system.ConstraintLoad(drive, last_time, last_y, lambda);
  SimeonState& s = run.end;
  s(0) = crank_angle;
  const mbs::MarkerRef rod_frame =
      system.Marker("rod", std::string(mbs::FlexibleBody::kOriginMarker));
  s(1) = angle_about_z(system.MarkerState(rod_frame, last_y).R_WM);
  s(2) = x_of(slider)(0);
  s.segment<n>(3) = x_of(rod).tail(n);
  s(7) = u_of(crank)(5);
  s(8) = u_of(rod)(5);
  s(9) = u_of(slider)(0);
  s.segment<n>(10) = u_of(rod).tail(n);
  s(14) = u_dot_of(crank)(5);
  s(15) = u_dot_of(rod)(5);
  s(16) = u_dot_of(slider)(0);
  s.segment<n>(17) = u_dot_of(rod).tail(n);
  // The rod end's force across W x is -lambda1 (the slider takes its reaction), the rod's force on
  // the slider -lambda2, the driving torque -lambda3.
  s(21) = on_slider.f_W.y();
  s(22) = -on_slider.f_W.x();
  s(23) = -on_crank.tau_W.z();
  return run;
}

}  // namespace flexmbs::validation
