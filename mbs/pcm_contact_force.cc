#include "mbs/pcm_contact_force.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <utility>

#include "contact/pcm/bvh.h"
#include "contact/pcm/candidate_pairs.h"
#include "contact/pcm/contact_element.h"
#include "contact/pcm/surface_checks.h"
#include "core/error.h"
#include "core/skew.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {
namespace {

/// The mesh placed in W by its marker, and its vertices' velocities [m/s].
struct PlacedMesh {
  contact::PolygonMesh mesh;
  Eigen::Matrix3Xd velocities_W;
};
PlacedMesh Place(const contact::PolygonMesh& mesh_M, const MarkerKinematics& marker) {
  PlacedMesh placed{mesh_M, Eigen::Matrix3Xd()};
  placed.mesh.vertices_W = (marker.R_WM * mesh_M.vertices_W).colwise() + marker.p_WM_W;
  const Eigen::Matrix3Xd r_W = placed.mesh.vertices_W.colwise() - marker.p_WM_W;
  placed.velocities_W.resize(3, r_W.cols());
  for (Eigen::Index v = 0; v < r_W.cols(); ++v) placed.velocities_W.col(v) = marker.v_WM_W + marker.w_WM_W.cross(r_W.col(v));
  return placed;
}

}  // namespace

PcmContactForce::PcmContactForce(std::string name, PcmSurface A, PcmSurface B, double areal_damping,
                                 const contact::RegularisedCoulomb& friction, double max_depth)
    : name_(std::move(name)), A_(std::move(A)), B_(std::move(B)), max_depth_(max_depth) {
  try {
    contact::RequirePcmSurface(A_.mesh_M, A_.name, A_.closed);
    contact::RequirePcmSurface(B_.mesh_M, B_.name, B_.closed);
    law_ = contact::MakeElasticFoundation(A_.layer, A_.name, B_.layer, B_.name, areal_damping, friction);
    if (!(max_depth > 0.0) || !std::isfinite(max_depth)) {
      throw InputError(fmt::format("max depth [m] {} must be finite and > 0", max_depth));
    }
  } catch (const InputError& e) {
    throw InputError(fmt::format("force element '{}': {}", name_, e.what()));
  }
}

struct PcmContactForce::Evaluation {
  MarkerKinematics marker_A, marker_B;
  PlacedMesh A, B;
  std::vector<contact::PcmElement> elements;
};

PcmContactForce::Evaluation PcmContactForce::Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const {
  Evaluation e{system.MarkerState(A_.marker, y), system.MarkerState(B_.marker, y), {}, {}, {}};
  e.A = Place(A_.mesh_M, e.marker_A);
  e.B = Place(B_.mesh_M, e.marker_B);
  e.elements = contact::ContactElements(
      e.A.mesh, e.B.mesh, contact::CandidatePairs(contact::Bvh(e.A.mesh), contact::Bvh(e.B.mesh, max_depth_)), max_depth_);
  return e;
}

void PcmContactForce::AddForces(double, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::VectorXd> h) const {
  const Evaluation e = Evaluate(system, y);
  if (e.elements.empty()) return;
  const contact::PairLoad load = contact::SumLoads(law_, e.elements, e.A.mesh, e.A.velocities_W, e.B.mesh,
                                                   e.B.velocities_W, e.marker_A.p_WM_W);
  // About B's origin: -(M_A + (p_A - p_B) x F).
  const Eigen::Vector3d moment_B = -(load.moment_W + (e.marker_A.p_WM_W - e.marker_B.p_WM_W).cross(load.force_W));
  system.AddMarkerLoad(A_.marker, e.marker_A, load.force_W, load.moment_W, h);
  system.AddMarkerLoad(B_.marker, e.marker_B, -load.force_W, moment_B, h);
}

double PcmContactForce::PotentialEnergy(double, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact::ElasticEnergy(law_, Evaluate(system, y).elements);
}

PcmContactForce::ElementState PcmContactForce::StateOf(const Evaluation& e, const contact::PcmElement& element) const {
  ElementState state{contact::Evaluate(law_, element,
                                       contact::RelativeVelocity(element, e.A.mesh, e.A.velocities_W, e.B.mesh,
                                                                 e.B.velocities_W)),
                     Eigen::Vector3d::Zero()};
  for (int k = 0; k < 3; ++k) {
    state.p_WA_W += element.weights_A(k) * e.A.mesh.vertices_W.col(e.A.mesh.face_vertices[3 * element.face_A + k]);
  }
  return state;
}

std::vector<ContactLoad> PcmContactForce::ContactLoads(double, const MultibodySystem& system,
                                                       const ConstVectorRef& y) const {
  const Evaluation e = Evaluate(system, y);
  std::vector<ContactLoad> loads;
  for (const contact::PcmElement& element : e.elements) {
    const auto [load, p_WA_W] = StateOf(e, element);
    if (load.normal_force > 0.0) loads.push_back({0, p_WA_W, element.normal_W, load.force_W});
  }
  return loads;
}

void PcmContactForce::AddForceJacobian(double, const MultibodySystem& system, const ConstVectorRef& y,
                                       Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  const Evaluation e = Evaluate(system, y);
  const std::array<std::pair<const MarkerRef*, const MarkerKinematics*>, 2> ends{
      std::pair{&A_.marker, &e.marker_A}, std::pair{&B_.marker, &e.marker_B}};
  const std::array<double, 2> signs{1.0, -1.0};
  for (const contact::PcmElement& element : e.elements) {
    const auto [load, p_WA_W] = StateOf(e, element);
    if (!(load.normal_force > 0.0)) continue;
    // The load acts at the pressure centre (rows); the relative velocity is that of A's point
    // under it against B's point at it (columns).
    const std::array<Eigen::Vector3d, 2> moving_points{p_WA_W, load.point_W};
    std::array<Eigen::MatrixXd, 2> J, J_moving;
    for (int i = 0; i < 2; ++i) {
      const MarkerKinematics& M = *ends[i].second;
      J[i] = M.jacobian.topRows<3>() - Skew(load.point_W - M.p_WM_W) * M.jacobian.bottomRows<3>();
      J_moving[i] = M.jacobian.topRows<3>() - Skew(moving_points[i] - M.p_WM_W) * M.jacobian.bottomRows<3>();
    }
    for (int i = 0; i < 2; ++i) {
      if (ends[i].first->is_ground()) continue;
      for (int j = 0; j < 2; ++j) {
        if (ends[j].first->is_ground()) continue;
        const Eigen::Index row = system.velocity_offset(ends[i].first->body);
        const Eigen::Index column = system.velocity_offset(ends[j].first->body);
        const double sign = signs[i] * signs[j];
        dh_dx.block(row, column, J[i].cols(), J[j].cols()) += sign * J[i].transpose() * load.d_displacement * J_moving[j];
        dh_du.block(row, column, J[i].cols(), J[j].cols()) += sign * J[i].transpose() * load.d_velocity * J_moving[j];
      }
    }
  }
}

}  // namespace flexmbs::mbs
