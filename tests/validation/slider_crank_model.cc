#include "tests/validation/slider_crank_model.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/planar.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/time_function.h"
#include "reduction/sid_body_builder.h"
#include "reduction/sid_spec.h"
#include "tests/fem/test_meshes.h"
#include "tests/support/test_problems.h"

namespace flexmbs::validation {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::Vector3d;

// A mode is in the plane when its reflection z -> -z (u_z negated, the nodes mirrored) differs
// from it by less than this share of its norm: the eigenvectors of the mirror-symmetric mesh are
// even or odd to round-off (measured ~1e-13).
constexpr double kMirrorSymmetry = 1e-6;
// Nodes are paired with their mirror images to this distance [m] (the mesh's round-off).
constexpr double kSameNode = 1e-12;

// mirror[n]: the node at (x, y, -z) of node n.
std::vector<Index> MirrorNodes(const fem::Mesh& mesh) {
  std::map<std::tuple<long, long, long>, Index> by_position;
  const auto key = [](const Vector3d& p) {
    return std::make_tuple(std::lround(p.x() / kSameNode), std::lround(p.y() / kSameNode), std::lround(p.z() / kSameNode));
  };
  for (Index n = 0; n < mesh.num_nodes(); ++n) by_position[key(mesh.nodes.col(n))] = n;
  std::vector<Index> mirror(static_cast<std::size_t>(mesh.num_nodes()));
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const Vector3d p = mesh.nodes.col(n);
    const auto found = by_position.find(key(Vector3d(p.x(), p.y(), -p.z())));
    FLEXMBS_CHECK(found != by_position.end(), "the rod's mesh is mirror-symmetric about z = 0");
    mirror[static_cast<std::size_t>(n)] = found->second;
  }
  return mirror;
}

}  // namespace

SliderCrankRod BuildRod(const SliderCrankData& data, const Eigen::Vector3i& cells) {
  FLEXMBS_CHECK(cells.x() % 2 == 0, "an even number of cells along the rod (the mid section is a node plane)");
  const fem::IsotropicMaterial steel = fem::testing::Steel();
  const double area = std::numbers::pi * data.rod_diameter * data.rod_diameter / 4.0;
  const double second_moment = area * data.rod_diameter * data.rod_diameter / 16.0;
  // b h = rho A / rho_steel, b h^3 / 12 = E I / E_steel.
  const double steel_area = data.density * area / steel.density_kg_m3;
  const double thickness = std::sqrt(12.0 * data.youngs_modulus * second_moment / (steel.youngs_modulus_pa * steel_area));
  LinkGeometry geometry;
  geometry.length = data.rod_length;
  geometry.thickness = thickness;
  geometry.width = steel_area / thickness;
  geometry.cells = cells;
  SliderCrankRod rod{BuildLink(geometry), {}};
  fem::Mesh& mesh = rod.link.mesh;
  mesh.node_sets["mid"] = flexmbs::testing::NodesOnPlane(mesh, 0, 0.5 * data.rod_length);

  const std::vector<Index> mirror = MirrorNodes(mesh);
  const Eigen::MatrixXd& Phi = rod.link.basis.Phi;
  for (Index k = 0; k < Phi.cols(); ++k) {
    Eigen::VectorXd reflected(Phi.rows());
    for (Index n = 0; n < mesh.num_nodes(); ++n) {
      const Index m = mirror[static_cast<std::size_t>(n)];
      reflected.segment<3>(3 * n) << Phi(3 * m, k), Phi(3 * m + 1, k), -Phi(3 * m + 2, k);
    }
    if ((reflected - Phi.col(k)).norm() <= kMirrorSymmetry * Phi.col(k).norm()) rod.in_plane_modes.push_back(k);
  }
  return rod;
}

sid::ReducedBody RodBody(const SliderCrankRod& rod, Index modes, bool stiffening) {
  FLEXMBS_CHECK(modes >= 1 && modes <= static_cast<Index>(rod.in_plane_modes.size()), "RodBody: modes in range");
  const reduction::ReducedBasis& all = rod.link.basis;
  const std::vector<Index> keep(rod.in_plane_modes.begin(), rod.in_plane_modes.begin() + modes);
  reduction::ReducedBasis basis = all;
  basis.Phi = all.Phi(Eigen::all, keep);
  basis.kinds.clear();
  basis.names.clear();
  for (const Index k : keep) {
    basis.kinds.push_back(all.kinds[static_cast<std::size_t>(k)]);
    basis.names.push_back(all.names[static_cast<std::size_t>(k)]);
  }
  basis.frequency_hz = all.frequency_hz(keep);
  basis.relative_residuals = all.relative_residuals(keep);
  basis.residual_floors = all.residual_floors(keep);
  basis.description = fmt::format("the lowest {} in-plane fixed-interface modes of the rod", modes);
  reduction::ComputeReducedMatrices({rod.link.K, rod.link.M, rod.link.mesh.nodes}, &basis);

  reduction::SidSpec sid;
  sid.markers = {{"tip", "tip", reduction::MarkerCoupling::kAveraging, std::nullopt, std::nullopt},
                 {"mid", "mid", reduction::MarkerCoupling::kAveraging, std::nullopt, std::nullopt}};
  sid.geometric_stiffening = stiffening;
  const fem::SystemMatrices views{rod.link.K, rod.link.M};
  sid::ReducedBody body =
      reduction::BuildReducedBody({rod.link.mesh, views, fem::MassMatrixKind::kConsistent, sid}, basis);
  body.name = "rod";
  return body;
}

CrankRun RunSliderCrank(const SliderCrankData& data, const sid::ReducedBody& rod_body, const CrankRunOptions& options) {
  mbs::MultibodySystem system(Vector3d::Zero());
  const Matrix3d I3 = Matrix3d::Identity();
  const Vector3d x = Vector3d::UnitX();
  // Crank: a steel bar of 10 x 10 mm (its inertia does not matter: the driver prescribes it).
  const double crank_mass = 7850.0 * 1e-4 * data.crank;
  const double crank_inertia = crank_mass * data.crank * data.crank / 12.0;
  system.AddBody(std::make_unique<mbs::RigidBody>(
      "crank", crank_mass, 0.5 * data.crank * x, Vector3d(1e-3 * crank_inertia, crank_inertia, crank_inertia).asDiagonal(),
      std::vector<mbs::RigidBodyMarker>{{"pivot", Vector3d::Zero(), I3}, {"pin", data.crank * x, I3}}));
  const int rod = system.AddBody(std::make_unique<mbs::FlexibleBody>("rod", rod_body, options.stiffening));
  // Slider: a point mass; its marker "guide" turns z onto B x (the prismatic joint's axis).
  const Matrix3d R_guide = Eigen::AngleAxisd(0.5 * std::numbers::pi, Vector3d::UnitY()).toRotationMatrix();
  const double slider_inertia = 1e-6;  // [kg m^2], locked by the prismatic joint
  const int slider = system.AddBody(std::make_unique<mbs::RigidBody>(
      "slider", data.slider_mass, Vector3d::Zero(), slider_inertia * I3,
      std::vector<mbs::RigidBodyMarker>{{"pin", Vector3d::Zero(), I3}, {"guide", Vector3d::Zero(), R_guide}}));
  const std::string origin(mbs::FlexibleBody::kOriginMarker);
  system.AddJoint(mbs::Joint("crank_drive", mbs::JointType::kRevolute, mbs::MarkerRef::Ground(Vector3d::Zero()),
                             system.Marker("crank", "pivot"), mbs::MakeSpinUp(data.spin, data.ramp_time)));
  system.AddJoint(mbs::Joint("crank_rod", mbs::JointType::kRevolute, system.Marker("crank", "pin"), system.Marker("rod", origin)));
  system.AddJoint(mbs::Joint("rod_slider", mbs::JointType::kRevolute, system.Marker("rod", "tip"), system.Marker("slider", "pin")));
  system.AddJoint(mbs::Joint("slider_guide", mbs::JointType::kPrismatic, mbs::MarkerRef::Ground(Vector3d::Zero(), R_guide),
                             system.Marker("slider", "guide")));

  // At rest at theta = 0: crank, rod and slider along W x.
  Eigen::VectorXd y0 = system.NeutralState();
  const Index n = rod_body.num_modes();
  Eigen::VectorXd x_rod = Eigen::VectorXd::Zero(7 + n);
  x_rod.head<4>() << data.crank, 0.0, 0.0, 1.0;
  system.SetBodyState(rod, x_rod, Eigen::VectorXd::Zero(6 + n), y0);
  Eigen::VectorXd x_slider(7);
  x_slider << data.crank + data.rod_length, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  system.SetBodyState(slider, x_slider, Eigen::VectorXd::Zero(6), y0);
  if (options.planar) mbs::MakePlanar(system, y0);

  const mbs::MarkerRef root = system.Marker("rod", origin), tip = system.Marker("rod", "tip"),
                       mid = system.Marker("rod", "mid");
  CrankRun run;
  const auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
    const Vector3d p_root = system.MarkerState(root, y).p_WM_W;
    const Vector3d chord = system.MarkerState(tip, y).p_WM_W - p_root;
    const Vector3d normal = Vector3d::UnitZ().cross(chord).normalized();
    run.time.push_back(t);
    run.mid_deflection.push_back(normal.dot(system.MarkerState(mid, y).p_WM_W - p_root));
  };
  const mbs::SimulationStatistics statistics = SimulateTimed(system, options.integrator, options.end_time,
                                                             options.output_interval, y0, record, &run.cpu_seconds);
  run.dropped_rows = static_cast<long>(statistics.initial_conditions.redundancy.dropped_rows.size());
  run.kept_velocities = static_cast<long>(system.KeptVelocities().size());
  run.kept_rows = static_cast<long>(system.KeptConstraints().size());
  run.steps = statistics.integrator.steps;
  run.rhs_evaluations = statistics.integrator.rhs_evaluations;
  return run;
}

double LargestDifference(const std::vector<double>& times, const std::vector<double>& a, const std::vector<double>& b,
                         double from, double to) {
  FLEXMBS_CHECK(a.size() == times.size() && b.size() == times.size(), "LargestDifference: histories of equal length");
  double largest = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (times[k] >= from && times[k] <= to) largest = std::max(largest, std::abs(a[k] - b[k]));
  }
  return largest;
}

}  // namespace flexmbs::validation
