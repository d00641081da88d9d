#include "contact/pcm/foundation.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <utility>

#include "contact/laws/law_checks.h"

namespace flexmbs::contact {

ElasticFoundation MakeElasticFoundation(const ElasticLayer& A, std::string_view name_A, const ElasticLayer& B,
                                        std::string_view name_B, double areal_damping, const RegularisedCoulomb& friction) {
  for (const auto& [layer, name] : {std::pair{&A, name_A}, std::pair{&B, name_B}}) {
    RequirePositive(fmt::format("layer modulus of surface '{}'", name), layer->modulus);
    RequirePositive(fmt::format("layer thickness of surface '{}'", name), layer->thickness);
  }
  RequireNonNegative("areal damping", areal_damping);
  ElasticFoundation law;
  law.stiffness = 1.0 / (A.thickness / A.modulus + B.thickness / B.modulus);
  law.areal_damping = areal_damping;
  law.friction = MakeRegularisedCoulomb(friction.coefficient, friction.regularisation_speed);
  return law;
}

double ElasticEnergy(const ElasticFoundation& law, const std::vector<PcmElement>& elements) {
  double depth_squared = 0.0;
  for (const PcmElement& element : elements) depth_squared += element.depth_squared;
  return 0.5 * law.stiffness * depth_squared;
}

ElementLoad Evaluate(const ElasticFoundation& law, const PcmElement& element, const Eigen::Vector3d& v_AB_W) {
  const Eigen::Vector3d& n = element.normal_W;
  const double v_N = n.dot(v_AB_W);
  ElementLoad load;
  load.point_W = element.pressure_centre_W;
  load.normal_force = std::max(0.0, law.stiffness * element.volume - law.areal_damping * element.area * v_N);
  load.force_W = load.normal_force * n;
  if (!(load.normal_force > 0.0)) return load;
  Eigen::Vector3d d_normal = n;  // dF/dF_N
  if (law.friction.coefficient > 0.0) {
    const TangentialForce friction = contact::Evaluate(law.friction, v_AB_W - v_N * n, load.normal_force);
    load.force_W += friction.force;
    d_normal += friction.d_normal_force;
    load.d_velocity = friction.d_slip * (Eigen::Matrix3d::Identity() - n * n.transpose());
  }
  load.d_velocity -= law.areal_damping * element.area * d_normal * n.transpose();
  load.d_displacement = -law.stiffness * element.area * d_normal * n.transpose();
  load.d_normal_force = d_normal;
  return load;
}

Eigen::Vector3d RelativeVelocity(const PcmElement& element, const PolygonMesh& A,
                                 const Eigen::Matrix3Xd& vertex_velocities_A_W, const PolygonMesh& B,
                                 const Eigen::Matrix3Xd& vertex_velocities_B_W) {
  const auto velocity = [](const PolygonMesh& mesh, const Eigen::Matrix3Xd& velocities, int face,
                           const Eigen::Vector3d& weights) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) v += weights(k) * velocities.col(mesh.face_vertices[3 * face + k]);
    return v;
  };
  return velocity(A, vertex_velocities_A_W, element.face_A, element.weights_A) -
         velocity(B, vertex_velocities_B_W, element.face_B, element.weights_B);
}

PairLoad SumLoads(const ElasticFoundation& law, const std::vector<PcmElement>& elements, const PolygonMesh& A,
                  const Eigen::Matrix3Xd& vertex_velocities_A_W, const PolygonMesh& B,
                  const Eigen::Matrix3Xd& vertex_velocities_B_W, const Eigen::Vector3d& p_W) {
  PairLoad pair;
  for (const PcmElement& element : elements) {
    const ElementLoad load =
        Evaluate(law, element, RelativeVelocity(element, A, vertex_velocities_A_W, B, vertex_velocities_B_W));
    pair.force_W += load.force_W;
    pair.moment_W += (load.point_W - p_W).cross(load.force_W);
    pair.normal_force += load.normal_force;
  }
  return pair;
}

}  // namespace flexmbs::contact
