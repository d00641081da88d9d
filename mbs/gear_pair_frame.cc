#include "mbs/gear_pair_frame.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

/// The cosine of the largest angle between the wheels' axes the planar mesh accepts (8.1 deg).
constexpr double kParallelAxes = 0.99;

}  // namespace

GearPairFrame MeasureGearPairFrame(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                   const MarkerRef& wheel1, const MarkerRef& wheel2,
                                   const contact::GearPair& pair, std::string_view name) {
  GearPairFrame f;
  f.wheel1 = system.MarkerState(wheel1, y);
  f.wheel2 = system.MarkerState(wheel2, y);
  const Eigen::Vector3d z = f.wheel1.R_WM.col(2);
  const double axes_cosine = z.dot(f.wheel2.R_WM.col(2));
  if (!(axes_cosine > kParallelAxes)) {
    throw SimulationError(
        t, fmt::format("t = {:.9g} s: spur gear contact '{}': the wheels' axes (the markers' z) "
                       "are {:.3g} deg apart; they must be parallel and point the same way",
                       t, name,
                       std::acos(std::clamp(axes_cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi));
  }
  const Eigen::Vector3d d = f.wheel2.p_WM_W - f.wheel1.p_WM_W;
  const Eigen::Vector3d in_plane = d - z.dot(d) * z;
  f.centre_distance = in_plane.norm();
  if (!(f.centre_distance > pair.gear1.base_radius + pair.gear2.base_radius)) {
    throw SimulationError(
        t, fmt::format("t = {:.9g} s: spur gear contact '{}': the axes are {:.6g} m apart, within "
                       "the sum of the base radii",
                       t, name, f.centre_distance));
  }
  f.x_W = in_plane / f.centre_distance;
  f.y_W = z.cross(f.x_W);
  f.p_WO_W = f.wheel1.p_WM_W + 0.5 * z.dot(d) * z;
  const auto angle = [&](const MarkerKinematics& m) {
    const Eigen::Vector3d x = m.R_WM.col(0);
    return std::atan2(x.dot(f.y_W), x.dot(f.x_W));
  };
  f.phi1 = angle(f.wheel1);
  f.phi2 = angle(f.wheel2);
  return f;
}

ContactPoint GearContactPoint(const GearPairFrame& f, const contact::ToothPair& tp, double penetration) {
  ContactPoint point;
  point.a = f.wheel2;
  point.b = f.wheel1;
  point.n_W = tp.n_12.x() * f.x_W + tp.n_12.y() * f.y_W;
  point.p_Wc_W = f.p_WO_W + tp.p_O1C.x() * f.x_W + tp.p_O1C.y() * f.y_W;
  point.penetration = penetration;
  return point;
}

void AddGearPairLoad(const MultibodySystem& system, const MarkerRef& wheel1, const MarkerRef& wheel2,
                     const ContactPoint& point, double force, Eigen::Ref<Eigen::VectorXd> h) {
  const Eigen::Vector3d f_W = force * point.n_W;
  system.AddMarkerLoad(wheel2, point.a, f_W, (point.p_Wc_W - point.a.p_WM_W).cross(f_W), h);
  system.AddMarkerLoad(wheel1, point.b, -f_W, (point.p_Wc_W - point.b.p_WM_W).cross(-f_W), h);
}

}  // namespace flexmbs::mbs
