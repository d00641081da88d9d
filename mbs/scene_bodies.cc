#include "mbs/scene_bodies.h"

#include <fmt/format.h>

#include <optional>

#include "core/error.h"
#include "core/rotation.h"
#include "mbs/flexible_body.h"
#include "mbs/mode_selection.h"
#include "mbs/rigid_body.h"
#include "mbs/scene_values.h"
#include "sid/sid_file.h"

namespace flexmbs::mbs {
namespace {

/// A 3 x 3 matrix as three rows of three numbers.
Eigen::Matrix3d ReadMatrix3(const YamlNode& node) {
  const std::vector<YamlNode> rows = node.AsList();
  if (rows.size() != 3) node.Fail(fmt::format("expected 3 rows of 3 numbers, got {} rows", rows.size()));
  Eigen::Matrix3d matrix;
  for (int r = 0; r < 3; ++r) matrix.row(r) = ReadVector3(rows[static_cast<std::size_t>(r)]).transpose();
  return matrix;
}

std::vector<RigidBodyMarker> ReadRigidMarkers(const YamlNode& node) {
  std::vector<RigidBodyMarker> markers;
  for (const auto& [name, item] : node.AsMap()) {
    item.RejectUnknownKeys({"position", "rotation"});
    RigidBodyMarker marker;
    marker.name = name;
    if (item.Has("position")) marker.p_BoM_B = ReadVector3(item.Required("position"));
    if (item.Has("rotation")) marker.R_BM = ReadRotation(item.Required("rotation"));
    markers.push_back(std::move(marker));
  }
  return markers;
}

/// `markers`: the body's `markers:` item, or null if it has none.
std::unique_ptr<Body> ReadRigid(const std::string& name, const YamlNode& node, const YamlNode* markers) {
  node.RejectUnknownKeys({"mass", "center_of_mass", "inertia"});
  const Eigen::Vector3d center = node.Has("center_of_mass") ? ReadVector3(node.Required("center_of_mass"))
                                                            : Eigen::Vector3d::Zero();
  try {
    return std::make_unique<RigidBody>(name, node.Required("mass").AsDouble(), center,
                                       ReadMatrix3(node.Required("inertia")),
                                       markers ? ReadRigidMarkers(*markers) : std::vector<RigidBodyMarker>{});
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

ModeSelection ReadModeSelection(const YamlNode& node) {
  node.RejectUnknownKeys({"names", "indices", "kinds", "max_frequency_hz"});
  ModeSelection selection;
  if (node.Has("names") || node.Has("indices")) {
    std::vector<ModeId> modes;
    if (node.Has("names")) {
      for (const std::string& mode : node.Required("names").AsStringList()) modes.emplace_back(mode);
    }
    if (node.Has("indices")) {
      for (const YamlNode& index : node.Required("indices").AsList()) modes.emplace_back(Eigen::Index{index.AsInt()});
    }
    selection.modes = std::move(modes);
  }
  if (node.Has("kinds")) selection.kinds = node.Required("kinds").AsStringList();
  if (node.Has("max_frequency_hz")) selection.max_frequency_hz = node.Required("max_frequency_hz").AsDouble();
  return selection;
}

std::unique_ptr<Body> ReadFlexible(const std::string& name, const YamlNode& node, const std::filesystem::path& folder,
                                   std::filesystem::path* file) {
  node.RejectUnknownKeys({"file", "modes", "geometric_stiffening"});
  const YamlNode file_node = node.Required("file");
  *file = folder / file_node.AsString();
  try {
    const sid::ReducedBody data = sid::ReadReducedBody(*file);
    const ModeSelection selection = node.Has("modes") ? ReadModeSelection(node.Required("modes")) : ModeSelection{};
    const bool stiffening = node.Has("geometric_stiffening") ? node.Required("geometric_stiffening").AsBool() : true;
    return std::make_unique<FlexibleBody>(name, RestrictModes(data, SelectModes(data, selection, name)), stiffening);
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

/// A vector of `size` finite numbers (a list), or zeros if `node` has no `key`.
Eigen::VectorXd ReadVectorOrZero(const YamlNode& node, std::string_view key, Eigen::Index size) {
  if (!node.Has(key)) return Eigen::VectorXd::Zero(size);
  const YamlNode item = node.Required(key);
  const std::vector<YamlNode> values = item.AsList();
  if (static_cast<Eigen::Index>(values.size()) != size) {
    item.Fail(fmt::format("expected {} numbers (one per kept mode), got {}", size, values.size()));
  }
  Eigen::VectorXd vector(size);
  for (Eigen::Index k = 0; k < size; ++k) vector(k) = values[static_cast<std::size_t>(k)].AsDouble();
  return vector;
}

/// The initial state from `initial:`: position p_WBo_W, rotation R_WB, velocity v_WBo_W,
/// angular velocity w_WB_W (world components, stored in B), modal coordinates and velocities.
void ReadInitialState(const YamlNode& node, Eigen::Index num_modes, SceneBody* body) {
  node.RejectUnknownKeys({"position", "rotation", "velocity", "angular_velocity", "modal_coordinates",
                          "modal_velocities"});
  const Eigen::Matrix3d R_WB = node.Has("rotation") ? ReadRotation(node.Required("rotation")) : Eigen::Matrix3d::Identity();
  body->x0.head<3>() = node.Has("position") ? ReadVector3(node.Required("position")) : Eigen::Vector3d::Zero();
  body->x0.segment<4>(3) = EulerParametersFromRotation(R_WB);
  body->x0.tail(num_modes) = ReadVectorOrZero(node, "modal_coordinates", num_modes);
  body->u0.head<3>() = node.Has("velocity") ? ReadVector3(node.Required("velocity")) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w_W =
      node.Has("angular_velocity") ? ReadVector3(node.Required("angular_velocity")) : Eigen::Vector3d::Zero();
  body->u0.segment<3>(3) = R_WB.transpose() * w_W;
  body->u0.tail(num_modes) = ReadVectorOrZero(node, "modal_velocities", num_modes);
}

}  // namespace

SceneBody ReadSceneBody(const std::string& name, const YamlNode& node, const std::filesystem::path& folder) {
  node.RejectUnknownKeys({"rigid", "flexible", "markers", "initial"});
  if (node.Has("rigid") == node.Has("flexible")) node.Fail("a body is either rigid or flexible (give exactly one)");
  SceneBody out;
  if (node.Has("rigid")) {
    out.kind = "rigid";
    const std::optional<YamlNode> markers =
        node.Has("markers") ? std::optional<YamlNode>(node.Required("markers")) : std::nullopt;
    out.body = ReadRigid(name, node.Required("rigid"), markers ? &*markers : nullptr);
  } else {
    if (node.Has("markers")) node.Required("markers").Fail("a flexible body's markers are the nodes of its .sid.h5 file");
    out.kind = "flexible";
    out.body = ReadFlexible(name, node.Required("flexible"), folder, &out.file);
  }
  const Eigen::Index n = out.body->num_modes();
  out.x0 = Eigen::VectorXd::Zero(7 + n);
  out.x0(3) = 1.0;
  out.u0 = Eigen::VectorXd::Zero(6 + n);
  if (node.Has("initial")) ReadInitialState(node.Required("initial"), n, &out);
  return out;
}

}  // namespace flexmbs::mbs
