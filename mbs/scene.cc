#include "mbs/scene.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <limits>
#include <string_view>
#include <utility>

#include "core/error.h"
#include "mbs/event_driven_scene.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/planar.h"
#include "mbs/scene_bodies.h"
#include "mbs/scene_contact.h"
#include "mbs/scene_unilateral.h"
#include "mbs/scene_values.h"

namespace flexmbs::mbs {
namespace {

/// Runs `build`, turning an InputError of the mbs classes into one naming `node`.
template <typename Build>
auto Within(const YamlNode& node, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

/// One end of a joint or force element: `{body: ground, position: [...], rotation: {...}}` or
/// `{body: <name>, marker: <name>}`.
MarkerRef ReadMarkerRef(const YamlNode& node, const MultibodySystem& system) {
  const std::string body = node.Required("body").AsString();
  if (body == "ground") {
    node.RejectUnknownKeys({"body", "position", "rotation"});
    return MarkerRef::Ground(node.Has("position") ? ReadVector3(node.Required("position")) : Eigen::Vector3d::Zero(),
                             node.Has("rotation") ? ReadRotation(node.Required("rotation")) : Eigen::Matrix3d::Identity());
  }
  node.RejectUnknownKeys({"body", "marker"});
  return Within(node, [&] { return system.Marker(body, node.Required("marker").AsString()); });
}

void ReadJoint(const YamlNode& node, MultibodySystem* system) {
  node.RejectUnknownKeys({"name", "type", "i", "j", "driver"});
  const std::string name = node.Required("name").AsString();
  const YamlNode type = node.Required("type");
  const JointType joint_type = Within(type, [&] { return ParseJointType(type.AsString()); });
  const MarkerRef i = ReadMarkerRef(node.Required("i"), *system);
  const MarkerRef j = ReadMarkerRef(node.Required("j"), *system);
  const TimeFunctionPtr driver = node.Has("driver") ? ReadTimeFunction(node.Required("driver")) : nullptr;
  Within(node, [&] { return system->AddJoint(Joint(name, joint_type, i, j, driver)); });
}

/// Three time functions (numbers or functions), or zeros if `key` is absent.
std::array<TimeFunctionPtr, 3> ReadFunctionVector(const YamlNode& node, std::string_view key) {
  std::array<TimeFunctionPtr, 3> functions{MakeConstant(0.0), MakeConstant(0.0), MakeConstant(0.0)};
  if (!node.Has(key)) return functions;
  const YamlNode item = node.Required(key);
  const std::vector<YamlNode> components = item.AsList();
  if (components.size() != 3) item.Fail(fmt::format("expected 3 components, got {}", components.size()));
  for (std::size_t a = 0; a < 3; ++a) functions[a] = ReadTimeFunction(components[a]);
  return functions;
}

Eigen::Matrix<double, 6, 1> ReadVector6(const YamlNode& node) {
  const std::vector<YamlNode> values = node.AsList();
  if (values.size() != 6) node.Fail(fmt::format("expected 6 numbers, got {}", values.size()));
  Eigen::Matrix<double, 6, 1> vector;
  for (int k = 0; k < 6; ++k) vector(k) = values[static_cast<std::size_t>(k)].AsDouble();
  return vector;
}

void ReadForceElement(const YamlNode& node, MultibodySystem* system, const SceneHooks& hooks) {
  const std::string name = node.Required("name").AsString();
  const YamlNode type_node = node.Required("type");
  const std::string type = type_node.AsString();
  std::unique_ptr<ForceElement> element;
  if (type == "point_load") {
    node.RejectUnknownKeys({"name", "type", "at", "force", "torque", "frame"});
    const MarkerRef at = ReadMarkerRef(node.Required("at"), *system);
    const LoadFrame frame =
        node.Has("frame") && node.Required("frame").AsChoice({"world", "marker"}) == 1 ? LoadFrame::kMarker
                                                                                        : LoadFrame::kWorld;
    element = Within(node, [&] {
      return std::make_unique<PointLoad>(name, at, ReadFunctionVector(node, "force"), ReadFunctionVector(node, "torque"),
                                         frame);
    });
  } else if (type == "spring_damper") {
    node.RejectUnknownKeys({"name", "type", "a", "b", "free_length", "stiffness", "damping"});
    const MarkerRef a = ReadMarkerRef(node.Required("a"), *system), b = ReadMarkerRef(node.Required("b"), *system);
    element = Within(node, [&] {
      return std::make_unique<SpringDamper>(name, a, b, node.Required("free_length").AsDouble(),
                                            node.Required("stiffness").AsDouble(),
                                            node.Has("damping") ? node.Required("damping").AsDouble() : 0.0);
    });
  } else if (type == "bushing") {
    node.RejectUnknownKeys({"name", "type", "i", "j", "stiffness", "damping"});
    const MarkerRef i = ReadMarkerRef(node.Required("i"), *system), j = ReadMarkerRef(node.Required("j"), *system);
    element = Within(node, [&] {
      return std::make_unique<Bushing>(name, i, j, ReadVector6(node.Required("stiffness")),
                                       node.Has("damping") ? ReadVector6(node.Required("damping"))
                                                           : Eigen::Matrix<double, 6, 1>::Zero());
    });
  } else if (IsContactForceType(type)) {
    element =
        ReadContactForce(node, name, type, *system, [&](const YamlNode& end) { return ReadMarkerRef(end, *system); },
                         hooks);
  } else {
    type_node.Fail(fmt::format("'{}' must be one of: point_load, spring_damper, bushing, {}", type,
                               fmt::join(kContactForceTypes, ", ")));
  }
  Within(node, [&] { return system->AddForceElement(std::move(element)); });
}

/// At most this many output samples (end_time / output_interval; docs/scene.md): 10^7 samples
/// of a single rigid body are already 1.3 GB of results.
constexpr double kMaxOutputSamples = 1e7;

/// A step below this many machine epsilons of end_time cannot advance the time (t + h rounds
/// to t near the end); docs/scene.md.
constexpr double kMinStepEpsilons = 64.0;

/// The number under `key` of `node`, if given, into `value`; > 0 or InputError at the item.
void ReadPositive(const YamlNode& node, std::string_view key, double* value) {
  if (!node.Has(key)) return;
  const YamlNode item = node.Required(key);
  *value = item.AsDouble();
  if (*value <= 0.0) item.Fail(fmt::format("{:g} must be > 0", *value));
}

/// end_time and output_interval of `simulation:` into `options` (> 0, and at most
/// kMaxOutputSamples outputs).
void ReadOutputTimes(const YamlNode& node, SimulationOptions* options) {
  options->end_time = node.Required("end_time").AsDouble();
  if (options->end_time <= 0.0) node.Required("end_time").Fail(fmt::format("{:g} must be > 0", options->end_time));
  options->output_interval = node.Has("output_interval") ? node.Required("output_interval").AsDouble()
                                                         : options->end_time / 100.0;
  if (options->output_interval <= 0.0) {
    node.Required("output_interval").Fail(fmt::format("{:g} must be > 0", options->output_interval));
  }
  if (options->end_time / options->output_interval > kMaxOutputSamples) {
    node.Required("output_interval")
        .Fail(fmt::format("{:g} s asks for {:.3g} samples up to end_time {:g} s, more than the limit of {:g}",
                          options->output_interval, options->end_time / options->output_interval, options->end_time,
                          kMaxOutputSamples));
  }
}

/// The ODE integrator's keys of `simulation:` (jacobian, newton, tolerances and steps) into
/// `integrator`, with the combinations it refuses checked here to name the scene's line
/// (OdeIntegrator refuses them too, but only when the run starts, after the results file is
/// opened). end_time [s] bounds the steps from below by the time's round-off.
void ReadIntegratorOptions(const YamlNode& node, double end_time, OdeOptions* integrator) {
  if (node.Has("jacobian") && node.Required("jacobian").AsChoice({"model", "difference_quotients"}) == 1) {
    integrator->jacobian = OdeJacobian::kDifferenceQuotients;
  }
  if (node.Has("newton")) {
    constexpr std::array<OdeNewton, 3> kNewton{OdeNewton::kAuto, OdeNewton::kDense, OdeNewton::kSparse};
    const int choice = node.Required("newton").AsChoice({"auto", "dense", "sparse"});
    integrator->newton = kNewton[static_cast<std::size_t>(choice)];
  }
  ReadPositive(node, "relative_tolerance", &integrator->relative_tolerance);
  ReadPositive(node, "absolute_tolerance", &integrator->absolute_tolerance);
  ReadPositive(node, "max_step", &integrator->max_step);
  ReadPositive(node, "fixed_step", &integrator->fixed_step);
  const double min_step = kMinStepEpsilons * std::numeric_limits<double>::epsilon() * end_time;
  for (const auto& [key, step] : {std::pair<std::string_view, double>{"max_step", integrator->max_step},
                                  {"fixed_step", integrator->fixed_step}}) {
    if (step > 0.0 && step < min_step) {
      node.Required(key).Fail(fmt::format("{:g} s is below the round-off of the time up to end_time {:g} s "
                                          "(at least {:g} epsilon x end_time = {:.3g} s)",
                                          step, end_time, kMinStepEpsilons, min_step));
    }
  }
  if (integrator->fixed_step > 0.0 && integrator->max_step > 0.0) {
    node.Required("max_step").Fail("excludes fixed_step (a fixed step has no adaptivity to bound): give one of them");
  }
  if (integrator->newton == OdeNewton::kSparse && integrator->jacobian == OdeJacobian::kDifferenceQuotients) {
    node.Required("newton").Fail(
        "sparse solves with the model Jacobian: set jacobian to model, or newton to dense or auto");
  }
}

/// Fails at the first key of `simulation:` that `method` (0 explicit, 2 moreau_jean) would read
/// and ignore: the Newton keys under the explicit method, the ODE integrator's keys under
/// Moreau-Jean (event_driven's are refused by ReadEventDrivenOptions).
void RejectKeysTheMethodDoesNotUse(const YamlNode& node, int method) {
  if (method == 0) {
    for (const std::string_view key : {"jacobian", "newton"}) {
      if (node.Has(key)) {
        node.Required(key).Fail("only for method implicit (the explicit method solves no Newton systems)");
      }
    }
  }
  if (method == 2) {
    for (const std::string_view key : {"relative_tolerance", "absolute_tolerance", "max_step", "fixed_step",
                                       "baumgarte_frequency", "jacobian", "newton"}) {
      if (node.Has(key)) {
        node.Required(key).Fail("not for method moreau_jean (fixed steps of size step, no ODE integrator)");
      }
    }
  }
}

SimulationOptions ReadSimulation(const YamlNode& node) {
  node.RejectUnknownKeys({"end_time", "output_interval", "method", "relative_tolerance", "absolute_tolerance",
                          "max_step", "fixed_step", "baumgarte_frequency", "jacobian", "newton", "redundant_pivot",
                          "step", "theta", "impact_level", "rest_velocity", "stick_velocity", "impact_law",
                          "gap_tolerance", "max_events"});
  SimulationOptions options;
  ReadOutputTimes(node, &options);
  const int method = node.Has("method")
                         ? node.Required("method").AsChoice({"explicit", "implicit", "moreau_jean", "event_driven"})
                         : 0;
  if (method == 1) options.integrator.method = OdeMethod::kImplicit;
  options.moreau_jean = ReadMoreauJeanOptions(node, method == 2);
  options.event_driven = ReadEventDrivenOptions(node, method == 3);
  ReadIntegratorOptions(node, options.end_time, &options.integrator);
  RejectKeysTheMethodDoesNotUse(node, method);
  ReadPositive(node, "baumgarte_frequency", &options.baumgarte_frequency);
  if (node.Has("redundant_pivot")) {
    const YamlNode item = node.Required("redundant_pivot");
    const double pivot = item.AsDouble();
    if (!(pivot >= options.singular_pivot && pivot < 1.0)) {
      item.Fail(fmt::format("{:g} must be in [{:g}, 1) (the singular pivot up to 1)", pivot, options.singular_pivot));
    }
    options.initial_conditions.redundant_pivot = pivot;
  }
  return options;
}

/// `paraview: true | false | {every: <n>}`.
ParaviewOutput ReadParaview(const YamlNode& node) {
  ParaviewOutput paraview;
  if (node.Has("every")) {
    node.RejectUnknownKeys({"every"});
    const YamlNode every = node.Required("every");
    paraview.enabled = true;
    paraview.every = every.AsInt();
    if (paraview.every < 1) every.Fail(fmt::format("{} must be >= 1", paraview.every));
    return paraview;
  }
  try {
    paraview.enabled = node.AsBool();
  } catch (const InputError&) {
    node.Fail("expected true, false or {every: <number of output samples>}");
  }
  return paraview;
}

/// `output: {markers: [body.marker, ...], paraview: ...}`.
std::vector<RecordedMarker> ReadOutput(const YamlNode& node, const MultibodySystem& system) {
  node.RejectUnknownKeys({"markers", "paraview"});
  std::vector<RecordedMarker> markers;
  if (!node.Has("markers")) return markers;
  for (const YamlNode& item : node.Required("markers").AsList()) {
    const std::string text = item.AsString();
    const std::size_t dot = text.find('.');
    if (dot == std::string::npos) item.Fail(fmt::format("'{}' must be <body>.<marker>", text));
    const MarkerRef ref = Within(item, [&] { return system.Marker(text.substr(0, dot), text.substr(dot + 1)); });
    markers.push_back({ref.body, ref.marker, text.substr(dot + 1)});
  }
  return markers;
}

}  // namespace

Scene LoadScene(const std::filesystem::path& file, const SceneHooks& hooks) {
  const YamlNode root = YamlNode::LoadFile(file);
  root.RejectUnknownKeys({"gravity", "planar", "bodies", "joints", "forces", "contacts", "simulation", "output"});
  Scene scene;
  scene.file = file;
  scene.system = std::make_unique<MultibodySystem>(root.Has("gravity") ? ReadVector3(root.Required("gravity"))
                                                                         : Eigen::Vector3d(0.0, 0.0, -9.81));
  std::vector<SceneBody> bodies;
  const YamlNode bodies_node = root.Required("bodies");
  for (const auto& [name, item] : bodies_node.AsMap()) {
    if (name == "ground") item.Fail("'ground' is the fixed frame; give the body another name");
    bodies.push_back(ReadSceneBody(name, item, file.parent_path()));
    SceneBody& body = bodies.back();
    scene.body_kinds.push_back(body.kind);
    scene.body_files.push_back(body.file);
    Within(item, [&] { return scene.system->AddBody(std::move(body.body)); });
  }
  if (root.Has("joints")) {
    for (const YamlNode& joint : root.Required("joints").AsList()) ReadJoint(joint, scene.system.get());
  }
  if (root.Has("forces")) {
    for (const YamlNode& element : root.Required("forces").AsList()) ReadForceElement(element, scene.system.get(), hooks);
  }
  scene.initial_state = scene.system->NeutralState();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    scene.system->SetBodyState(static_cast<int>(b), bodies[b].x0, bodies[b].u0, scene.initial_state);
  }
  scene.options = ReadSimulation(root.Required("simulation"));
  if (root.Has("contacts")) {
    const YamlNode contacts = root.Required("contacts");
    for (const YamlNode& item : contacts.AsList()) {
      std::unique_ptr<UnilateralContact> contact = ReadUnilateralContact(
          item, *scene.system, [&](const YamlNode& end) { return ReadMarkerRef(end, *scene.system); });
      if (scene.options.event_driven && scene.options.event_driven->impact_law == ImpactLaw::kPoisson &&
          contact->law().friction > 0.0) {
        item.Required("friction").Fail(fmt::format("{:g}: impact_law poisson takes frictionless contacts (friction 0); "
                                                   "Coulomb friction with impact_law newton",
                                                   contact->law().friction));
      }
      if (scene.options.moreau_jean && scene.options.moreau_jean->impact_level == ImpactLevel::kPosition &&
          contact->law().restitution > 0.0) {
        item.Required("restitution")
            .Fail(fmt::format("{:g}: impact_level position takes no restitution (the points' impacts follow from "
                              "the step's positions); velocity level for e > 0",
                              contact->law().restitution));
      }
      if (!scene.options.moreau_jean && !scene.options.event_driven) {
        item.Fail(fmt::format("contact '{}' is unilateral, which only simulation.method moreau_jean or "
                              "event_driven integrates (compliant contact under explicit or implicit: the force elements sphere_plane_contact, "
                              "sphere_sphere_contact)",
                              contact->name()));
      }
      Within(item, [&] { return scene.system->AddUnilateralContact(std::move(contact)); });
    }
  }
  if (root.Has("planar")) {
    const YamlNode planar = root.Required("planar");
    if (planar.AsString() != "xy") planar.Fail(fmt::format("'{}': the planar scenes' plane is xy", planar.AsString()));
    Within(planar, [&] { MakePlanar(*scene.system, scene.initial_state); });
  }
  if (root.Has("output")) {
    const YamlNode output = root.Required("output");
    scene.recorded_markers = ReadOutput(output, *scene.system);
    if (output.Has("paraview")) scene.paraview = ReadParaview(output.Required("paraview"));
  }
  return scene;
}

}  // namespace flexmbs::mbs
