#include "tests/validation/flexible_pendulum_model.h"

#include <fmt/format.h>
#include <time.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <utility>

#include "core/error.h"
#include "fem/assembly.h"
#include "mbs/flexible_body.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/mode_selection.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/time_function.h"
#include "eigensolvers/eigensolver.h"
#include "reduction/sid_body_builder.h"
#include "reduction/sid_spec.h"
#include "tests/fem/test_meshes.h"
#include "tests/support/test_problems.h"

namespace flexmbs::validation {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::Vector3d;

const Vector3d kGravity_W(0.0, 0.0, -9.81);  // [m/s^2]

// The start pose R_WB0 of the link and the hub: x along W x, z (the hinge axis) along W y, so
// the link's y points down.
Eigen::Quaterniond StartRotation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(-0.5 * std::numbers::pi, Vector3d::UnitX()));
}

const sid::Node& TipNode(const sid::ReducedBody& body) {
  const auto tip = std::find_if(body.nodes.begin(), body.nodes.end(), [](const sid::Node& n) { return n.name == "tip"; });
  FLEXMBS_CHECK(tip != body.nodes.end(), "the link has a tip marker");
  return *tip;
}

// The hub as a rigid body with its frame on the hinge (z the axis) and marker "hinge" there.
std::unique_ptr<mbs::RigidBody> MakeHub(const Hub& hub) {
  const double mass = fem::testing::Steel().density_kg_m3 * std::numbers::pi * hub.radius * hub.radius * hub.thickness;
  const double axial = 0.5 * mass * hub.radius * hub.radius;
  const double diametral = mass * (3.0 * hub.radius * hub.radius + hub.thickness * hub.thickness) / 12.0;
  return std::make_unique<mbs::RigidBody>("hub", mass, Vector3d::Zero(), Vector3d(diametral, diametral, axial).asDiagonal().toDenseMatrix(),
                                          std::vector<mbs::RigidBodyMarker>{{"hinge", Vector3d::Zero(), Matrix3d::Identity()}});
}

}  // namespace

double ProcessCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

mbs::SimulationStatistics SimulateTimed(mbs::MultibodySystem& system, const mbs::OdeOptions& integrator,
                                        double end_time, double output_interval, const Eigen::VectorXd& y0,
                                        const mbs::OutputCallback& record, double* cpu_seconds) {
  mbs::SimulationOptions simulation;
  simulation.integrator = integrator;
  simulation.end_time = end_time;
  simulation.output_interval = output_interval;
  const double start = ProcessCpuSeconds();
  const mbs::SimulationStatistics statistics = mbs::Simulate(system, simulation, y0, record);
  *cpu_seconds = ProcessCpuSeconds() - start;
  return statistics;
}

FeLink BuildLink(const LinkGeometry& geometry) {
  FeLink link;
  link.geometry = geometry;
  const Vector3d size(geometry.length, geometry.thickness, geometry.width);
  link.mesh = fem::testing::StructuredBox(fem::ElementType::kHex20, geometry.cells, size).mesh;
  for (fem::ElementBlock& block : link.mesh.blocks) block.material = fem::testing::Steel();
  // The root face centred on Bo.
  fem::testing::Transform(&link.mesh, Matrix3d::Identity(), Vector3d(0.0, -0.5 * size.y(), -0.5 * size.z()));
  const std::vector<int> root = flexmbs::testing::NodesOnPlane(link.mesh, 0, 0.0);
  link.mesh.node_sets["root"] = root;
  link.mesh.node_sets["tip"] = flexmbs::testing::NodesOnPlane(link.mesh, 0, geometry.length);
  fem::SystemMatrices system = fem::AssembleSystem(link.mesh, fem::MassMatrixKind::kConsistent);
  link.K = std::move(system.stiffness);
  link.M = std::move(system.mass);

  std::vector<bool> clamped(static_cast<std::size_t>(link.mesh.num_dofs()), false);
  for (const int node : root) {
    for (int a = 0; a < 3; ++a) clamped[static_cast<std::size_t>(3 * node + a)] = true;
  }
  for (Index d = 0; d < link.mesh.num_dofs(); ++d) {
    if (!clamped[static_cast<std::size_t>(d)]) link.free_dofs.push_back(static_cast<int>(d));
  }
  const Eigen::SparseMatrix<double> K_oo = fem::testing::Submatrix(link.K, link.free_dofs, link.free_dofs);
  const Eigen::SparseMatrix<double> M_oo = fem::testing::Submatrix(link.M, link.free_dofs, link.free_dofs);
  // The clamped K_oo is positive definite: shift 0.
  const flexmbs::testing::DenseEigen eigen = flexmbs::testing::SolveDense(K_oo, M_oo, 0.0);
  link.eigenvalues = eigen.values;

  reduction::ReducedBasis& basis = link.basis;
  const Index n = eigen.values.size();
  basis.method = "fixed_interface_modal";
  basis.description = fmt::format("every fixed-interface normal mode ({}), dense solve", n);
  basis.Phi = Eigen::MatrixXd::Zero(link.mesh.num_dofs(), n);
  basis.Phi(link.free_dofs, Eigen::all) = eigen.vectors;
  for (Index k = 0; k < n; ++k) {
    basis.kinds.push_back(reduction::ModeKind::kNormal);
    basis.names.push_back(fmt::format("normal_{}", k + 1));
  }
  basis.frequency_hz = eigensolvers::FrequenciesHz(eigen.values);
  const eigensolvers::PairResiduals residuals = eigensolvers::ComputeResiduals(K_oo, M_oo, eigen.values, eigen.vectors, 0.0);
  basis.relative_residuals = residuals.relative;
  basis.residual_floors = residuals.floor;
  basis.held_by.supports.push_back({"root", root});
  basis.eigensolver = "dense";
  reduction::ComputeReducedMatrices({link.K, link.M, link.mesh.nodes}, &basis);

  reduction::SidSpec sid;
  sid.markers = {{"tip", "tip", reduction::MarkerCoupling::kAveraging, std::nullopt, std::nullopt}};
  sid.geometric_stiffening = false;
  const fem::SystemMatrices views{link.K, link.M};
  link.body = reduction::BuildReducedBody({link.mesh, views, fem::MassMatrixKind::kConsistent, sid}, basis);
  link.body.name = "link";
  return link;
}

sid::ReducedBody FirstModes(const sid::ReducedBody& body, Index n) {
  std::vector<Index> keep(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k) keep[static_cast<std::size_t>(k)] = k;
  return mbs::RestrictModes(body, keep);
}

Eigen::VectorXd HeldDeflection(const sid::ReducedBody& body) {
  return body.Ke.m0.ldlt().solve(body.Ct.m0 * (StartRotation().toRotationMatrix().transpose() * kGravity_W));
}

Swing RunSwing(const sid::ReducedBody& body, const SwingOptions& options) {
  mbs::MultibodySystem system(kGravity_W);
  const int hub = system.AddBody(MakeHub(options.hub));
  const int link = system.AddBody(std::make_unique<mbs::FlexibleBody>("link", body, false));
  const Eigen::Quaterniond e0 = StartRotation();
  const mbs::MarkerRef hinge = system.Marker("hub", "hinge");
  system.AddJoint(mbs::Joint("hinge", mbs::JointType::kRevolute, mbs::MarkerRef::Ground(Vector3d::Zero(), e0.toRotationMatrix()), hinge));
  system.AddJoint(mbs::Joint("clamp", mbs::JointType::kFixed, hinge,
                             system.Marker("link", std::string(mbs::FlexibleBody::kOriginMarker))));
  const mbs::MarkerRef tip = system.Marker("link", "tip");

  // Held: the brake's torque about the hinge (W y) balances gravity's moment (R0 mdCM(q0)) x g_W
  // on the deflected link (the hub's centre is on the hinge).
  const Index n = body.num_modes();
  const Eigen::VectorXd q0 = HeldDeflection(body);
  Vector3d mdCM = body.mdCM.m0.col(0);
  for (Index j = 0; j < n; ++j) mdCM += body.mdCM.m1[static_cast<std::size_t>(j)] * q0(j);
  const double holding_torque = -(e0.toRotationMatrix() * mdCM).cross(kGravity_W).y();
  system.AddForceElement(std::make_unique<mbs::PointLoad>(
      "brake", hinge, std::array<mbs::TimeFunctionPtr, 3>{},
      std::array<mbs::TimeFunctionPtr, 3>{
          nullptr, mbs::MakeSmoothStep(0.0, holding_torque, options.release_time, 0.0, mbs::SmoothStepOrder::kQuintic), nullptr},
      mbs::LoadFrame::kWorld));

  Eigen::VectorXd y0 = system.NeutralState();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(7 + n);
  x.segment<4>(3) << e0.w(), e0.x(), e0.y(), e0.z();
  x.tail(n) = q0;
  system.SetBodyState(link, x, Eigen::VectorXd::Zero(6 + n), y0);
  system.SetBodyState(hub, x.head<7>(), Eigen::VectorXd::Zero(6), y0);

  const Vector3d p_BoTip_B = TipNode(body).origin.m0;
  Swing swing;
  const auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
    const auto x_b = system.BodyPositions(y, link);
    const Eigen::Quaterniond e(x_b(3), x_b(4), x_b(5), x_b(6));
    const Vector3d p_WTip_W = system.MarkerState(tip, y).p_WM_W;
    const Vector3d p_BoTip_B_now = e.toRotationMatrix().transpose() * (p_WTip_W - x_b.head<3>());
    const Eigen::Quaterniond turn = e0.conjugate() * e;  // about B0's z
    swing.time.push_back(t);
    swing.tip_deflection.push_back(p_BoTip_B_now.y() - p_BoTip_B.y());
    swing.hinge_angle.push_back(2.0 * std::atan2(turn.z(), turn.w()));
    swing.energy.push_back(system.KineticEnergy(y) + system.PotentialEnergy(t, y));
  };

  const mbs::SimulationStatistics statistics = SimulateTimed(system, options.integrator, options.end_time,
                                                             options.output_interval, y0, record, &swing.cpu_seconds);
  swing.steps = statistics.integrator.steps;
  swing.rhs_evaluations = statistics.integrator.rhs_evaluations;
  return swing;
}

SwingDeviation Deviation(const Swing& swing, const Swing& reference) {
  FLEXMBS_CHECK(swing.time == reference.time, "swings recorded at the same times");
  SwingDeviation d;
  for (std::size_t k = 0; k < swing.time.size(); ++k) {
    d.tip_deflection = std::max(d.tip_deflection, std::abs(swing.tip_deflection[k] - reference.tip_deflection[k]));
    d.hinge_angle = std::max(d.hinge_angle, std::abs(swing.hinge_angle[k] - reference.hinge_angle[k]));
  }
  return d;
}

double LargestTipDeflection(const Swing& swing) {
  double largest = 0.0;
  for (const double w : swing.tip_deflection) largest = std::max(largest, std::abs(w));
  return largest;
}

double EnergyDriftAfterRelease(const Swing& swing, double release_time) {
  const auto released = std::lower_bound(swing.time.begin(), swing.time.end(), release_time);
  FLEXMBS_CHECK(released != swing.time.end(), "the swing lasts beyond the release");
  const std::size_t first = static_cast<std::size_t>(released - swing.time.begin());
  double drift = 0.0;
  for (std::size_t k = first; k < swing.energy.size(); ++k) {
    drift = std::max(drift, std::abs(swing.energy[k] - swing.energy[first]));
  }
  return drift;
}

double SwingEnergyScale(const sid::ReducedBody& body) {
  return body.mass * kGravity_W.norm() * std::abs(body.center_of_mass.x());
}

}  // namespace flexmbs::validation
