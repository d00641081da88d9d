#include "mbs/joint.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "mbs/constraint_rows.h"

namespace flexmbs::mbs {
namespace {

constexpr int kX = 0, kY = 1, kZ = 2;

struct TypeInfo {
  JointType type;
  std::string_view name;
  Eigen::Index equations;
};

constexpr std::array<TypeInfo, 6> kTypes = {{{JointType::kFixed, "fixed", 6},
                                             {JointType::kRevolute, "revolute", 5},
                                             {JointType::kPrismatic, "prismatic", 5},
                                             {JointType::kCylindrical, "cylindrical", 4},
                                             {JointType::kSpherical, "spherical", 3},
                                             {JointType::kUniversal, "universal", 4}}};

const TypeInfo& Info(JointType type) {
  for (const TypeInfo& info : kTypes) {
    if (info.type == type) return info;
  }
  FLEXMBS_CHECK(false, "joint: unknown type");
  return kTypes[0];
}

void AppendTypeRows(JointType type, const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows) {
  switch (type) {
    case JointType::kFixed:
      AppendCoincidence(I, J, rows);
      AppendRelativeRotation(I, J, rows);
      return;
    case JointType::kRevolute:
      AppendCoincidence(I, J, rows);
      AppendAxesDot(kX, kZ, I, J, rows);
      AppendAxesDot(kY, kZ, I, J, rows);
      return;
    case JointType::kPrismatic:
      AppendAxisOffset(kX, I, J, rows);
      AppendAxisOffset(kY, I, J, rows);
      AppendAxesDot(kX, kZ, I, J, rows);
      AppendAxesDot(kY, kZ, I, J, rows);
      AppendAxesDot(kY, kX, I, J, rows);
      return;
    case JointType::kCylindrical:
      AppendAxisOffset(kX, I, J, rows);
      AppendAxisOffset(kY, I, J, rows);
      AppendAxesDot(kX, kZ, I, J, rows);
      AppendAxesDot(kY, kZ, I, J, rows);
      return;
    case JointType::kSpherical:
      AppendCoincidence(I, J, rows);
      return;
    case JointType::kUniversal:
      AppendCoincidence(I, J, rows);
      AppendAxesDot(kX, kY, I, J, rows);
      return;
  }
}

Eigen::Matrix<double, 12, 1> SpatialVelocities(const MarkerKinematics& I, const MarkerKinematics& J) {
  Eigen::Matrix<double, 12, 1> V;
  V << I.v_WM_W, I.w_WM_W, J.v_WM_W, J.w_WM_W;
  return V;
}

// The revolute driver's row c = cos(theta) (y_I . x_J) - sin(theta) (x_I . x_J) = sin(phi - theta)
// for J's x axis at angle phi about z_I, with theta = theta(t). Its explicit time terms:
// g_t = -theta' (sin(theta) c_yx + cos(theta) c_xx), and the part of d2c/dt2 not in D A + Ddot V,
// 2 dc/dt|_t + c_tt (returned in time_terms).
void AppendAngleDriver(const TimeFunctionValue& theta, const MarkerKinematics& I, const MarkerKinematics& J,
                       ConstraintRows& rows, double& g_t, double& time_terms) {
  ConstraintRows parts(2);
  AppendAxesDot(kY, kX, I, J, parts);
  AppendAxesDot(kX, kX, I, J, parts);
  const double c = std::cos(theta.value), s = std::sin(theta.value);
  const double w = theta.first_derivative, a = theta.second_derivative;
  const Eigen::Vector2d coefficient(c, -s), rate(-s * w, -c * w), acceleration(-a * s - w * w * c, -a * c + w * w * s);
  const Eigen::Vector2d part_rate = parts.D * SpatialVelocities(I, J);
  FLEXMBS_CHECK(rows.filled < rows.value.size(), "joint: no row reserved for the angle driver");
  const Eigen::Index r = rows.filled++;
  rows.value(r) = coefficient.dot(parts.value);
  rows.D.row(r) = coefficient.transpose() * parts.D;
  rows.velocity_product(r) = coefficient.dot(parts.velocity_product);
  g_t = rate.dot(parts.value);
  time_terms = 2.0 * rate.dot(part_rate) + acceleration.dot(parts.value);
}

// The prismatic driver's row c = z_I . (p_J - p_I) - s(t).
void AppendOffsetDriver(const TimeFunctionValue& s, const MarkerKinematics& I, const MarkerKinematics& J,
                        ConstraintRows& rows, double& g_t, double& time_terms) {
  const Eigen::Index r = rows.filled;
  AppendAxisOffset(kZ, I, J, rows);
  rows.value(r) -= s.value;
  g_t = -s.first_derivative;
  time_terms = -s.second_derivative;
}

}  // namespace

std::string_view JointTypeName(JointType type) { return Info(type).name; }

JointType ParseJointType(std::string_view name) {
  for (const TypeInfo& info : kTypes) {
    if (info.name == name) return info.type;
  }
  throw InputError(fmt::format(
      "unknown joint type '{}' (known: fixed, revolute, prismatic, cylindrical, spherical, universal)", name));
}

Joint::Joint(std::string name, JointType type, MarkerRef marker_i, MarkerRef marker_j, TimeFunctionPtr driver)
    : name_(std::move(name)), type_(type), marker_i_(std::move(marker_i)), marker_j_(std::move(marker_j)),
      driver_(std::move(driver)) {
  if (driver_ && type_ != JointType::kRevolute && type_ != JointType::kPrismatic) {
    throw InputError(fmt::format("joint '{}': a driver needs a revolute or prismatic joint, not {}", name_,
                                 JointTypeName(type_)));
  }
  if (marker_i_.body == marker_j_.body) {
    throw InputError(fmt::format("joint '{}': both markers are on the same {}", name_,
                                 marker_i_.is_ground() ? std::string("ground") : fmt::format("body (index {})", marker_i_.body)));
  }
}

Eigen::Index Joint::num_equations() const { return Info(type_).equations + (driver_ ? 1 : 0); }

JointEquations Joint::Evaluate(double t, const MarkerKinematics& I, const MarkerKinematics& J) const {
  const Eigen::Index m = num_equations();
  ConstraintRows rows(m);
  AppendTypeRows(type_, I, J, rows);
  JointEquations out;
  out.g_t = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd time_terms = Eigen::VectorXd::Zero(m);
  if (driver_) {
    const TimeFunctionValue value = driver_->Evaluate(t);
    if (type_ == JointType::kRevolute) {
      AppendAngleDriver(value, I, J, rows, out.g_t(m - 1), time_terms(m - 1));
    } else {
      AppendOffsetDriver(value, I, J, rows, out.g_t(m - 1), time_terms(m - 1));
    }
  }
  FLEXMBS_CHECK(rows.filled == m, fmt::format("joint '{}': {} rows for {} equations", name_, rows.filled, m));
  out.g = rows.value;
  out.G_i = rows.D.leftCols<6>() * I.jacobian;
  out.G_j = rows.D.rightCols<6>() * J.jacobian;
  out.gamma = -(rows.D.leftCols<6>() * I.bias + rows.D.rightCols<6>() * J.bias + rows.velocity_product + time_terms);
  out.D_J = rows.D.rightCols<6>();
  return out;
}

}  // namespace flexmbs::mbs
