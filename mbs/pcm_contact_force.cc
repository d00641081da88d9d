#include "mbs/pcm_contact_force.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <utility>

#include "contact/pcm/contact_element.h"
#include "contact/pcm/surface_checks.h"
#include "core/error.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

PcmContactForce::PcmContactForce(std::string name, PcmSurface A, PcmSurface B, double areal_damping,
                                 const contact::RegularisedCoulomb& friction, double max_depth,
                                 PcmTreeUpdate tree_update)
    : name_(std::move(name)), A_(std::move(A)), B_(std::move(B)), max_depth_(max_depth), tree_update_(tree_update),
      trees_(std::make_unique<TreeCache>()) {
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
  PlacedPcmSurface A, B;
  std::vector<contact::PcmElement> elements;
};

std::vector<contact::FacePair> PcmContactForce::CandidatePairs(const contact::PolygonMesh& A,
                                                               const contact::PolygonMesh& B) const {
  std::unique_lock<std::mutex> lock(trees_->mutex, std::try_to_lock);
  if (tree_update_ == PcmTreeUpdate::kRebuild || !lock.owns_lock()) {
    if (lock.owns_lock()) trees_->builds += 2;
    return contact::CandidatePairs(contact::Bvh(A), contact::Bvh(B, max_depth_));
  }
  const auto update = [&](std::optional<contact::Bvh>& tree, const contact::PolygonMesh& mesh, double depth) {
    if (!tree) {
      tree.emplace(mesh, depth);
      ++trees_->builds;
      return;
    }
    tree->Refit(mesh);
    if (tree->Degradation() > kRebuildDegradation) {
      tree->Rebuild(mesh);
      ++trees_->builds;
    }
  };
  update(trees_->A, A, 0.0);
  update(trees_->B, B, max_depth_);
  return contact::CandidatePairs(*trees_->A, *trees_->B);
}

int PcmContactForce::tree_builds() const {
  const std::lock_guard<std::mutex> lock(trees_->mutex);
  return trees_->builds;
}

PcmContactForce::Evaluation PcmContactForce::Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const {
  Evaluation e{PlacedPcmSurface(system, A_, y), PlacedPcmSurface(system, B_, y), {}};
  e.elements = contact::ContactElements(e.A.mesh(), e.B.mesh(), CandidatePairs(e.A.mesh(), e.B.mesh()), max_depth_);
  return e;
}

void PcmContactForce::AddForces(double, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::VectorXd> h) const {
  const Evaluation e = Evaluate(system, y);
  if (e.elements.empty()) return;
  const MarkerKinematics &frame_A = e.A.frame(), &frame_B = e.B.frame();
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero(), moment_W = Eigen::Vector3d::Zero();  // on A, about A's origin
  Eigen::VectorXd modal_A = Eigen::VectorXd::Zero(A_.modal.phi.cols()), modal_B = Eigen::VectorXd::Zero(B_.modal.phi.cols());
  for (const contact::PcmElement& element : e.elements) {
    const contact::ElementLoad load = StateOf(e, element).load;
    if (!(load.normal_force > 0.0)) continue;
    force_W += load.force_W;
    moment_W += (load.point_W - frame_A.p_WM_W).cross(load.force_W);
    if (A_.is_modal()) modal_A += e.A.ModalJacobian(element.face_A, element.weights_A).transpose() * load.force_W;
    if (B_.is_modal()) modal_B -= e.B.ModalJacobian(element.face_B, element.weights_B).transpose() * load.force_W;
  }
  // About B's origin: -(M_A + (p_A - p_B) x F).
  const Eigen::Vector3d moment_B = -(moment_W + (frame_A.p_WM_W - frame_B.p_WM_W).cross(force_W));
  system.AddMarkerLoad(A_.marker, frame_A, force_W, moment_W, h);
  system.AddMarkerLoad(B_.marker, frame_B, -force_W, moment_B, h);
  if (A_.is_modal()) h.segment(e.A.modal_column(), modal_A.size()) += modal_A;
  if (B_.is_modal()) h.segment(e.B.modal_column(), modal_B.size()) += modal_B;
}

double PcmContactForce::PotentialEnergy(double, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact::ElasticEnergy(law_, Evaluate(system, y).elements);
}

PcmContactForce::ElementState PcmContactForce::StateOf(const Evaluation& e, const contact::PcmElement& element) const {
  ElementState state{contact::Evaluate(law_, element,
                                       contact::RelativeVelocity(element, e.A.mesh(), e.A.velocities_W(), e.B.mesh(),
                                                                 e.B.velocities_W())),
                     Eigen::Vector3d::Zero()};
  for (int k = 0; k < 3; ++k) {
    state.p_WA_W += element.weights_A(k) * e.A.mesh().vertices_W.col(e.A.mesh().face_vertices[3 * element.face_A + k]);
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
  const std::array<const PcmSurface*, 2> sides{&A_, &B_};
  const std::array<const PlacedPcmSurface*, 2> placed{&e.A, &e.B};
  const std::array<double, 2> signs{1.0, -1.0};
  for (const contact::PcmElement& element : e.elements) {
    const auto [load, p_WA_W] = StateOf(e, element);
    if (!(load.normal_force > 0.0)) continue;
    // Side i's material point of the element as a function of the point x in the patch:
    // J_i(x) = J_i(x_p) + sum_d G_i,d (x - x_p)_d (rows: the load's point; the relative velocity
    // is that of A's point under x against B's point at x, the columns J'_i).
    const std::array<int, 2> faces{element.face_A, element.face_B};
    const std::array<Eigen::Vector3d, 2> weights{element.weights_A, element.weights_B};
    const std::array<Eigen::Matrix3d, 2> gradients{element.weight_gradients_A, element.weight_gradients_B};
    const std::array<Eigen::Vector3d, 2> moving_points{p_WA_W, load.point_W};
    std::array<Eigen::MatrixXd, 2> J, J_moving;
    std::array<std::array<Eigen::MatrixXd, 3>, 2> G;
    for (int i = 0; i < 2; ++i) {
      J[i] = placed[i]->PointJacobian(load.point_W, faces[i], weights[i]);
      J_moving[i] = placed[i]->PointJacobian(moving_points[i], faces[i], weights[i]);
      for (int d = 0; d < 3; ++d) G[i][d] = placed[i]->PointJacobianGradient(faces[i], gradients[i], d);
    }
    const Eigen::Vector3d& n = element.normal_W;
    const Eigen::Vector3d& m = element.first_moment_W;
    const Eigen::Matrix3d& S = element.second_moment_W;
    for (int i = 0; i < 2; ++i) {
      if (sides[i]->marker.is_ground()) continue;
      // G_i,e^T F: how the load's virtual work moves with its point, per coordinate e of x_p.
      std::array<Eigen::VectorXd, 3> lever;
      for (int d = 0; d < 3; ++d) lever[d] = G[i][d].transpose() * load.force_W;
      for (int j = 0; j < 2; ++j) {
        if (sides[j]->marker.is_ground()) continue;
        // A displacement dz of side j changes the depth at x by -s_j n^T J'_j(x) dz: the volume by
        // -s_j n^T (A J'_j + sum_d m_d G_j,d) dz and the pressure centre by -s_j (m n^T J'_j +
        // sum_d S_:d n^T G_j,d) dz / V. The load's derivative is then the consistent
        // c integral(J_i(x)^T d_F n^T J'_j(x) dA) over the patch.
        Eigen::RowVectorXd volume_rate = element.area * n.transpose() * J_moving[j];
        Eigen::MatrixXd centre_rate = m * (n.transpose() * J_moving[j]);
        for (int d = 0; d < 3; ++d) {
          const Eigen::RowVectorXd normal_gradient = n.transpose() * G[j][d];
          volume_rate += m(d) * normal_gradient;
          centre_rate += S.col(d) * normal_gradient;
        }
        Eigen::MatrixXd block = -law_.stiffness * J[i].transpose() * load.d_normal_force * volume_rate;
        for (int d = 0; d < 3; ++d) block -= lever[d] * centre_rate.row(d) / element.volume;
        const Eigen::Index row = system.velocity_block(sides[i]->marker.body).start;
        const Eigen::Index column = system.velocity_block(sides[j]->marker.body).start;
        const double sign = signs[i] * signs[j];
        dh_dx.block(row, column, J[i].cols(), J[j].cols()) += sign * block;
        dh_du.block(row, column, J[i].cols(), J[j].cols()) += sign * J[i].transpose() * load.d_velocity * J_moving[j];
      }
    }
  }
}

}  // namespace flexmbs::mbs
