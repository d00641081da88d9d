#include "mbs/planar.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/mirror_symmetry.h"
#include "core/rotation.h"
#include "mbs/flexible_body.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;

[[noreturn]] void Refuse(const std::string& item, const std::string& problem) {
  throw InputError(fmt::format("{}: {}", item, problem));
}

/// mirror[n]: the FE node at (x, y, -z) of node n (B components), paired to kMirrorDistance of
/// the mesh's size (core/mirror_symmetry.h); refuses a mesh that is not mirror-symmetric about B's
/// xy plane.
std::vector<Index> MirrorNodes(const FlexibleBody& body) {
  const Eigen::Matrix3Xd& nodes = body.data().node_positions;
  const std::vector<Index> mirror = MirrorPointsAboutXy(nodes, kMirrorDistance);
  for (Index n = 0; n < nodes.cols(); ++n) {
    if (mirror[static_cast<std::size_t>(n)] >= 0) continue;
    const Eigen::Vector3d p = nodes.col(n);
    Refuse(fmt::format("body '{}'", body.name()),
           fmt::format("its FE mesh is not mirror-symmetric about its xy plane: node {} at ({:g}, {:g}, {:g}) m has no "
                       "mirror image",
                       n, p.x(), p.y(), p.z()));
  }
  return mirror;
}

/// The modes of a flexible body that move in the plane, as columns of its velocity block (6 + j):
/// those even under the reflection z -> -z of B (the nodes mirrored, u_z negated; odd modes move
/// out of the plane). Refuses a mode that is neither, or a body without mode shapes on its nodes.
std::vector<Index> InPlaneModeColumns(const FlexibleBody& body) {
  const Eigen::MatrixXd& phi = body.data().phi;
  const Index n = body.num_modes();
  if (n == 0) return {};
  if (phi.cols() != n || phi.rows() != 3 * body.data().node_positions.cols() || phi.rows() == 0) {
    Refuse(fmt::format("body '{}'", body.name()),
           "its file carries no mode shapes on the FE nodes to tell in-plane from out-of-plane modes");
  }
  const Eigen::MatrixXd reflected = ReflectedAboutXy(MirrorNodes(body), phi);
  std::vector<Index> columns;
  for (Index j = 0; j < n; ++j) {
    const double norm = phi.col(j).norm();
    const double even = (reflected.col(j) - phi.col(j)).norm() / norm;
    const double odd = (reflected.col(j) + phi.col(j)).norm() / norm;
    if (even <= kPlanarModeSymmetry) {
      columns.push_back(6 + j);
    } else if (odd > kPlanarModeSymmetry) {
      Refuse(fmt::format("body '{}' mode {} '{}'", body.name(), j + 1, body.data().mode_names.at(static_cast<std::size_t>(j))),
             fmt::format("neither in-plane nor out-of-plane: it departs from its reflection z -> -z by {:.3g} and from "
                         "its negative by {:.3g} of its norm",
                         even, odd));
    }
  }
  return columns;
}

/// Body b's kept columns after the checks of its initial state and mass matrix.
std::vector<Index> CheckBody(const MultibodySystem& system, int b, const ConstVectorRef& y0) {
  const Body& body = system.body(b);
  const std::string item = fmt::format("body '{}'", body.name());
  std::vector<Index> kept = {0, 1, 5};
  if (const auto* flexible = dynamic_cast<const FlexibleBody*>(&body)) {
    for (const Index column : InPlaneModeColumns(*flexible)) kept.push_back(column);
  } else if (body.num_modes() > 0) {
    Refuse(item, "a body with modes that is not a reduced flexible body");
  }
  const auto x = system.BodyPositions(y0, b);
  const auto u = system.BodyVelocities(y0, b);
  if (std::abs(x(4)) > kPlanarTolerance || std::abs(x(5)) > kPlanarTolerance) {
    Refuse(item, fmt::format("initial rotation's Euler parameters ({:g}, {:g}, {:g}, {:g}) turn about an axis out of z",
                             x(3), x(4), x(5), x(6)));
  }
  const Eigen::MatrixXd M = system.BodyMassMatrix(b, y0);
  // M's translation-rotation block is R mdCM~^T: mdCM = m p_BoCm_B.
  const Eigen::Matrix3d R_WB = RotationFromEulerParameters(x.segment<4>(3));
  const Eigen::Matrix3d mdCM_tilde = -R_WB.transpose() * M.block<3, 3>(0, 3);
  const Eigen::Vector3d p_WCm_W = x.head<3>() + R_WB * Eigen::Vector3d(mdCM_tilde(2, 1), mdCM_tilde(0, 2), mdCM_tilde(1, 0)) / M(0, 0);
  const double length = std::max(1.0, x.head<3>().norm());
  if (std::abs(p_WCm_W.z()) > kPlanarTolerance * length) {
    Refuse(item, fmt::format("initial centre of mass ({:g}, {:g}, {:g}) m is off the plane z = 0", p_WCm_W.x(),
                             p_WCm_W.y(), p_WCm_W.z()));
  }
  std::vector<char> is_kept(static_cast<std::size_t>(u.size()), 0);
  for (const Index column : kept) is_kept[static_cast<std::size_t>(column)] = 1;
  const double speed = std::max(1.0, u(kept).cwiseAbs().maxCoeff());
  static constexpr const char* kRigidNames[6] = {"v_x", "v_y", "v_z", "w_B_x", "w_B_y", "w_B_z"};
  for (Index i = 0; i < u.size(); ++i) {
    if (is_kept[static_cast<std::size_t>(i)] != 0) continue;
    const std::string name = i < 6 ? kRigidNames[i] : fmt::format("qdot of mode {}", i - 5);
    if (std::abs(u(i)) > kPlanarTolerance * speed) Refuse(item, fmt::format("initial {} = {:g} is out of the plane", name, u(i)));
    if (i >= 6 && std::abs(x(i + 1)) > 0.0) {
      Refuse(item, fmt::format("initial q of out-of-plane mode {} = {:g} must be 0", i - 5, x(i + 1)));
    }
    for (const Index k : kept) {
      const double coupling = M(k, i) / std::sqrt(M(k, k) * M(i, i));
      if (std::abs(coupling) > kPlanarCoupling) {
        const std::string kept_name = k < 6 ? kRigidNames[k] : fmt::format("mode {}", k - 5);
        Refuse(item, fmt::format("its mass matrix couples the in-plane {} with the out-of-plane {}: M = {:.6g} ({:.3g} of "
                                 "sqrt(M_ii M_jj); a rigid body's centre of mass off its xy plane or J_xz, J_yz not 0)",
                                 kept_name, i < 6 ? kRigidNames[i] : fmt::format("mode {}", i - 5), M(k, i), coupling));
      }
    }
  }
  return kept;
}

/// Refuses a joint whose axis does not fit the plane at y0.
void CheckJoint(const MultibodySystem& system, const Joint& joint, const ConstVectorRef& y0) {
  const Eigen::Vector3d z_I = system.MarkerState(joint.marker_i(), y0).R_WM.col(2);
  const bool along_z = z_I.head<2>().norm() <= kPlanarTolerance, in_plane = std::abs(z_I.z()) <= kPlanarTolerance;
  const std::string item = fmt::format("joint '{}' ({})", joint.name(), JointTypeName(joint.type()));
  const std::string axis = fmt::format("({:g}, {:g}, {:g})", z_I.x(), z_I.y(), z_I.z());
  switch (joint.type()) {
    case JointType::kRevolute:
      if (!along_z) Refuse(item, fmt::format("axis {} must be z", axis));
      break;
    case JointType::kPrismatic:
      if (!in_plane) Refuse(item, fmt::format("axis {} must lie in the plane xy", axis));
      break;
    case JointType::kCylindrical:
      if (!along_z && !in_plane) Refuse(item, fmt::format("axis {} must be z or lie in the plane xy", axis));
      break;
    case JointType::kUniversal:
      Refuse(item, "a universal joint has no planar form (a revolute about z)");
    case JointType::kFixed:
    case JointType::kSpherical:
      break;
  }
}

}  // namespace

Eigen::Vector3d PlanarTangent(const Eigen::Vector3d& n_W) { return Eigen::Vector3d::UnitZ().cross(n_W); }

Index ContactDimension(const MultibodySystem& system) { return system.planar() ? 2 : 3; }

ContactTangents Tangents(const UnilateralContactKinematics& c, Index d) {
  FLEXMBS_CHECK(d == 2 || d == 3, "Tangents: d is 2 or 3");
  if (d == 3) {
    Eigen::Matrix3Xd t_W(3, 2);
    t_W << c.t1_W, c.t2_W;
    return {t_W, c.W_T};
  }
  const Eigen::Vector3d t = PlanarTangent(c.n_W);
  return {t, t.dot(c.t1_W) * c.W_T.row(0) + t.dot(c.t2_W) * c.W_T.row(1)};
}

void UsePlanarTangents(UnilateralContactKinematics& c) {
  const Eigen::Vector3d t1 = PlanarTangent(c.n_W), t2 = Eigen::Vector3d::UnitZ();
  Eigen::Matrix2d turn;
  turn << t1.dot(c.t1_W), t1.dot(c.t2_W), t2.dot(c.t1_W), t2.dot(c.t2_W);
  c.W_T = (turn * c.W_T).eval();
  c.t1_W = t1;
  c.t2_W = t2;
}

void MakePlanar(MultibodySystem& system, const ConstVectorRef& y0) {
  const Eigen::Vector3d& g_W = system.gravity();
  if (std::abs(g_W.z()) > kPlanarTolerance * std::max(1.0, g_W.norm())) {
    Refuse("gravity", fmt::format("({:g}, {:g}, {:g}) m/s^2 has the out-of-plane component {:g}", g_W.x(), g_W.y(),
                                  g_W.z(), g_W.z()));
  }
  std::vector<std::vector<Index>> kept;
  for (int b = 0; b < system.num_bodies(); ++b) kept.push_back(CheckBody(system, b, y0));
  for (int k = 0; k < system.num_joints(); ++k) CheckJoint(system, system.joint(k), y0);
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    const UnilateralContact& contact = system.unilateral_contact(k);
    for (const UnilateralContactKinematics& point : contact.Evaluate(0.0, system, y0)) {
      if (std::abs(point.n_W.z()) > kPlanarTolerance) {
        Refuse(fmt::format("contact '{}'", contact.name()),
               fmt::format("normal ({:g}, {:g}, {:g}) is out of the plane xy", point.n_W.x(), point.n_W.y(), point.n_W.z()));
      }
    }
  }
  system.set_kept_velocities(std::move(kept));
}

}  // namespace flexmbs::mbs
