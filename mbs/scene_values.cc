#include "mbs/scene_values.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::mbs {
namespace {

std::vector<double> ReadNumbers(const YamlNode& node) {
  std::vector<double> values;
  for (const YamlNode& item : node.AsList()) values.push_back(item.AsDouble());
  return values;
}

double OptionalDouble(const YamlNode& node, std::string_view key, double fallback) {
  return node.Has(key) ? node.Required(key).AsDouble() : fallback;
}

/// Runs a factory of time_function.h, turning its InputError into one naming `node`.
template <typename Factory>
TimeFunctionPtr Make(const YamlNode& node, Factory factory) {
  try {
    return factory();
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

}  // namespace

double ReadPositiveLength(const YamlNode& node, std::string_view key, std::string_view owner) {
  const YamlNode item = node.Required(key);
  const double length = item.AsDouble();
  if (!(length > 0.0)) item.Fail(fmt::format("{}: {:g} m must be > 0", owner, length));
  return length;
}

Eigen::Vector3d ReadVector3(const YamlNode& node) {
  const std::vector<YamlNode> xyz = node.AsList();
  if (xyz.size() != 3) node.Fail(fmt::format("expected 3 numbers, got {}", xyz.size()));
  return Eigen::Vector3d(xyz[0].AsDouble(), xyz[1].AsDouble(), xyz[2].AsDouble());
}

Eigen::Matrix3d ReadRotation(const YamlNode& node) {
  node.RejectUnknownKeys({"axis", "angle"});
  const YamlNode axis_node = node.Required("axis");
  const Eigen::Vector3d axis = ReadVector3(axis_node);
  if (axis.norm() == 0.0) axis_node.Fail("a rotation axis must not be zero");
  return Eigen::AngleAxisd(node.Required("angle").AsDouble(), axis.normalized()).toRotationMatrix();
}

TimeFunctionPtr ReadTimeFunction(const YamlNode& node) {
  if (!node.Has("ramp") && !node.Has("polynomial") && !node.Has("harmonic") && !node.Has("smooth_step") &&
      !node.Has("spin_up") && !node.Has("table")) {
    return MakeConstant(node.AsDouble());  // a number, or an InputError naming the item
  }
  node.RejectUnknownKeys({"ramp", "polynomial", "harmonic", "smooth_step", "spin_up", "table"});
  if (node.AsMap().size() != 1) {
    node.Fail("a time function is exactly one of ramp, polynomial, harmonic, smooth_step, spin_up, table");
  }
  if (node.Has("ramp")) {
    const YamlNode ramp = node.Required("ramp");
    ramp.RejectUnknownKeys({"offset", "slope"});
    return Make(ramp, [&] { return MakeRamp(OptionalDouble(ramp, "offset", 0.0), ramp.Required("slope").AsDouble()); });
  }
  if (node.Has("polynomial")) {
    const YamlNode polynomial = node.Required("polynomial");
    return Make(polynomial, [&] { return MakePolynomial(ReadNumbers(polynomial)); });
  }
  if (node.Has("harmonic")) {
    const YamlNode harmonic = node.Required("harmonic");
    harmonic.RejectUnknownKeys({"amplitude", "angular_frequency", "phase", "offset"});
    return Make(harmonic, [&] {
      return MakeHarmonic(harmonic.Required("amplitude").AsDouble(), harmonic.Required("angular_frequency").AsDouble(),
                          OptionalDouble(harmonic, "phase", 0.0), OptionalDouble(harmonic, "offset", 0.0));
    });
  }
  if (node.Has("smooth_step")) {
    const YamlNode step = node.Required("smooth_step");
    step.RejectUnknownKeys({"t0", "f0", "t1", "f1", "order"});
    SmoothStepOrder order = SmoothStepOrder::kQuintic;
    if (step.Has("order") && step.Required("order").AsChoice({"cubic", "quintic"}) == 0) {
      order = SmoothStepOrder::kCubic;
    }
    return Make(step, [&] {
      return MakeSmoothStep(step.Required("t0").AsDouble(), step.Required("f0").AsDouble(),
                            step.Required("t1").AsDouble(), step.Required("f1").AsDouble(), order);
    });
  }
  if (node.Has("spin_up")) {
    const YamlNode spin_up = node.Required("spin_up");
    spin_up.RejectUnknownKeys({"rate", "ramp_time", "offset"});
    return Make(spin_up, [&] {
      return MakeSpinUp(spin_up.Required("rate").AsDouble(), spin_up.Required("ramp_time").AsDouble(),
                        OptionalDouble(spin_up, "offset", 0.0));
    });
  }
  const YamlNode table = node.Required("table");
  table.RejectUnknownKeys({"times", "values"});
  return Make(table, [&] { return MakeCubicSpline(ReadNumbers(table.Required("times")), ReadNumbers(table.Required("values"))); });
}

}  // namespace flexmbs::mbs
