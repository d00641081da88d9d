// `flexmbs simulate`: load a scene, integrate it and write its results file.
#include <chrono>
#include <cmath>
#include <ctime>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "app/command_support.h"
#include "app/commands.h"
#include "app/fe_tooth_table.h"
#include "app/gear_results.h"
#include "core/error.h"
#include "core/sha256.h"
#include "mbs/contact_mode_advice.h"
#include "mbs/constraint_projection.h"
#include "mbs/flexible_body.h"
#include "mbs/paraview_writer.h"
#include "mbs/results_file.h"
#include "mbs/scene.h"
#include "mbs/simulation_error.h"

namespace flexmbs::app {
namespace {

struct SimulateOptions {
  std::string scene_file;
  std::string output;
  bool json = false;
};

mbs::ResultsLayout Layout(const mbs::Scene& scene, const mbs::ConsistencyReport& initial) {
  const mbs::MultibodySystem& system = *scene.system;
  mbs::ResultsLayout layout;
  for (int b = 0; b < system.num_bodies(); ++b) {
    mbs::ResultsLayout::Body body{system.body(b).name(), scene.body_kinds[static_cast<std::size_t>(b)], {}, {}};
    if (const auto* flexible = dynamic_cast<const mbs::FlexibleBody*>(&system.body(b))) {
      body.mode_names = flexible->data().mode_names;
    }
    for (const mbs::RecordedMarker& marker : scene.recorded_markers) {
      if (marker.body == b) body.markers.push_back(marker.name);
    }
    layout.bodies.push_back(std::move(body));
  }
  for (int k = 0; k < system.num_joints(); ++k) {
    layout.joints.push_back({system.joint(k).name(), std::string(mbs::JointTypeName(system.joint(k).type()))});
  }
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    const mbs::UnilateralContact& contact = system.unilateral_contact(k);
    layout.contacts.push_back({contact.name(), std::string(contact.type())});
  }
  layout.element_series = GearSeries(system);
  layout.events = scene.options.event_driven.has_value();
  const mbs::OdeOptions& ode = scene.options.integrator;
  const std::string jacobian = ode.method == mbs::OdeMethod::kImplicit
                                   ? fmt::format(", jacobian {}, newton {}", mbs::OdeJacobianName(ode.jacobian),
                                                 mbs::OdeNewtonName(ode.newton))
                                   : "";
  layout.provenance = {{"scene_file", scene.file.string()},
                       {"scene_sha256", Sha256OfFile(scene.file)},
                       {"integrator", scene.options.moreau_jean
                                          ? fmt::format("moreau_jean, step {:g}, theta {:g}",
                                                        scene.options.moreau_jean->step, scene.options.moreau_jean->theta)
                                          : fmt::format("{}{}, rtol {:g}, atol {:g}{}",
                                                        scene.options.event_driven ? "event_driven, between events " : "",
                                                        mbs::OdeMethodName(ode.method), ode.relative_tolerance,
                                                        ode.absolute_tolerance, jacobian)},
                       {"redundant_constraints", initial.redundancy.Describe(system)}};
  for (std::size_t b = 0; b < scene.body_files.size(); ++b) {
    if (scene.body_files[b].empty()) continue;
    layout.provenance["body_file " + system.body(static_cast<int>(b)).name()] =
        fmt::format("{} (sha256 {})", scene.body_files[b].string(), Sha256OfFile(scene.body_files[b]));
  }
  return layout;
}

/// The results of one output time; `contacts` is the report of the Moreau-Jean output interval
/// that ended at t (empty for the ODE methods, which have no unilateral contacts).
mbs::ResultsSample Sample(const mbs::Scene& scene, double t, const Eigen::VectorXd& y, const Eigen::VectorXd& lambda,
                          const mbs::MoreauJeanStepReport& contacts) {
  const mbs::MultibodySystem& system = *scene.system;
  mbs::ResultsSample sample;
  sample.time = t;
  sample.marker_positions.resize(static_cast<std::size_t>(system.num_bodies()));
  for (int b = 0; b < system.num_bodies(); ++b) {
    sample.positions.emplace_back(system.BodyPositions(y, b));
    sample.velocities.emplace_back(system.BodyVelocities(y, b));
  }
  for (const mbs::RecordedMarker& marker : scene.recorded_markers) {
    sample.marker_positions[static_cast<std::size_t>(marker.body)].push_back(
        system.MarkerState(mbs::MarkerRef::OnBody(marker.body, marker.marker), y).p_WM_W);
  }
  for (int k = 0; k < system.num_joints(); ++k) {
    const mbs::JointLoad load = system.ConstraintLoad(k, t, y, lambda);
    sample.joint_forces.push_back(load.f_W);
    sample.joint_torques.push_back(load.tau_W);
  }
  for (const mbs::ContactStepResult& contact : contacts.contacts) {
    sample.contacts.push_back({contact.g_N, contact.P_N, contact.P_T, contact.active, contact.sliding});
  }
  sample.element_rows = GearRows(system, t, y);
  sample.kinetic_energy = system.KineticEnergy(y);
  sample.potential_energy = system.PotentialEnergy(t, y);
  const mbs::ConstraintResidual residual = mbs::MeasureConstraints(system, t, y);
  sample.constraint_position = residual.position;
  sample.constraint_velocity = residual.velocity;
  return sample;
}

/// "sparse" or "dense": how an implicit run solved its Newton systems (auto picks by size).
std::string_view NewtonUsed(const mbs::OdeStatistics& statistics) {
  return mbs::OdeNewtonName(statistics.sparse_newton ? mbs::OdeNewton::kSparse : mbs::OdeNewton::kDense);
}

/// The mode advice as JSON (mbs/contact_mode_advice.h).
nlohmann::json AdviceJson(const std::vector<mbs::ContactModeAdvice>& advice) {
  nlohmann::json list = nlohmann::json::array();
  for (const mbs::ContactModeAdvice& a : advice) {
    list.push_back({{"element", a.element},
                    {"type", a.type},
                    {"body", a.body},
                    {"unilateral", a.unilateral},
                    {"first_points", a.first_points},
                    {"effective_mass_kg", a.effective_mass},
                    {"impact_speed_m_s", a.impact_speed},
                    {"law_stiffness", a.law_stiffness},
                    {"law_exponent", a.law_exponent},
                    {"contact_time_s", a.contact_time},
                    {"correction_mode", a.correction_mode},
                    {"cutoff_hz", a.cutoff_hz},
                    {"loaded_modes", a.loaded_modes},
                    {"loaded_modes_above_cutoff", a.loaded_modes_above},
                    {"highest_loaded_hz", a.highest_loaded_hz},
                    {"reason", a.Describe()}});
  }
  return list;
}

/// The report as JSON (keys documented in docs/cli.md).
nlohmann::json ReportJson(const SimulateOptions& options, const mbs::Scene& scene,
                          const mbs::SimulationStatistics& stats,
                          const std::vector<mbs::ContactModeAdvice>& advice, double energy_start,
                          double energy_end) {
  nlohmann::json j;
  j["output"] = options.output;
  j["bodies"] = scene.system->num_bodies();
  j["joints"] = scene.system->num_joints();
  j["end_time"] = scene.options.end_time;
  j["outputs"] = stats.outputs;
  j["steps"] = stats.integrator.steps;
  j["rhs_evaluations"] = stats.integrator.rhs_evaluations;
  j["error_test_failures"] = stats.integrator.error_test_failures;
  if (scene.options.moreau_jean) {
    j["contact_solves"] = stats.moreau_jean.contact_solves;
    j["max_active_contacts"] = stats.moreau_jean.max_active_contacts;
    j["contact_solver_iterations"] = stats.moreau_jean.solver_iterations;
    j["max_contact_solver_error"] = stats.moreau_jean.max_solver_error;
    j["contact_solve_cpu_seconds"] = stats.moreau_jean.contact_solve_cpu_seconds;
  }
  if (scene.options.event_driven) {
    const mbs::EventDrivenStatistics& events = stats.event_driven;
    j["events"] = events.events;
    j["impacts"] = events.impacts;
    j["separations"] = events.separations;
    j["closings"] = events.closings;
    j["sticks"] = events.sticks;
    j["slips"] = events.slips;
    j["max_impact_points"] = events.max_impact_points;
    j["max_lcp_error"] = events.max_lcp_error;
    j["contact_solve_cpu_seconds"] = events.contact_solve_cpu_seconds;
  }
  if (scene.options.integrator.method == mbs::OdeMethod::kImplicit) {
    j["newton"] = NewtonUsed(stats.integrator);
    j["newton_iterations"] = stats.integrator.newton_iterations;
    j["newton_setups"] = stats.integrator.newton_setups;
  }
  j["mode_advice"] = AdviceJson(advice);
  j["initial_conditions"] = stats.initial_conditions.Describe(*scene.system);
  nlohmann::json dropped = nlohmann::json::array();
  const mbs::ConstraintRedundancy& redundancy = stats.initial_conditions.redundancy;
  for (std::size_t k = 0; k < redundancy.dropped_rows.size(); ++k) {
    dropped.push_back(redundancy.DescribeRow(*scene.system, k));
  }
  j["redundant_constraints"] = dropped;
  j["dropped_row_violation"] = stats.dropped_row_violation;
  j["dropped_row_limit_share"] = stats.dropped_row_limit_share;
  j["energy_j"] = {{"start", energy_start}, {"end", energy_end}};
  j["wall_seconds"] = stats.wall_seconds;
  j["real_time_factor"] = stats.wall_seconds / (scene.options.end_time - scene.options.start_time);
  return j;
}

/// The report as text lines: the scene, its initial state, the integration and its contacts,
/// events and Newton solves, the mode advice, the energy and the time.
void PrintReportText(const SimulateOptions& options, const mbs::Scene& scene,
                     const mbs::SimulationStatistics& stats,
                     const std::vector<mbs::ContactModeAdvice>& advice, double energy_start,
                     double energy_end) {
  const double simulated = scene.options.end_time - scene.options.start_time;
  fmt::print("wrote           {}\n", options.output);
  fmt::print("scene           {} bodies, {} joints, {} force elements\n", scene.system->num_bodies(),
             scene.system->num_joints(), scene.system->num_force_elements());
  fmt::print("initial state   {}\n", stats.initial_conditions.Describe(*scene.system));
  fmt::print("redundant       {}\n", stats.initial_conditions.redundancy.Describe(*scene.system));
  if (!stats.initial_conditions.redundancy.dropped_rows.empty()) {
    fmt::print("dropped rows    largest violation {:.3g} ({:.2g} of its limit)\n", stats.dropped_row_violation,
               stats.dropped_row_limit_share);
  }
  fmt::print("integration     {} steps, {} function evaluations, {} error-test failures\n", stats.integrator.steps,
             stats.integrator.rhs_evaluations, stats.integrator.error_test_failures);
  if (scene.options.moreau_jean) {
    fmt::print("contacts        {} unilateral: {} steps with contact, at most {} active, {} solver iterations, largest "
               "error {:.3g}, {:.3g} s of CPU\n",
               scene.system->num_unilateral_contacts(), stats.moreau_jean.contact_solves,
               stats.moreau_jean.max_active_contacts, stats.moreau_jean.solver_iterations,
               stats.moreau_jean.max_solver_error, stats.moreau_jean.contact_solve_cpu_seconds);
  }
  if (scene.options.event_driven) {
    fmt::print("events          {} ({} impacts, at most {} points in one, {} closings, {} separations, {} sticks, "
               "{} slips), largest contact-solve error {:.3g}, contact solves {:.3g} s of CPU\n",
               stats.event_driven.events, stats.event_driven.impacts, stats.event_driven.max_impact_points,
               stats.event_driven.closings, stats.event_driven.separations, stats.event_driven.sticks,
               stats.event_driven.slips, stats.event_driven.max_lcp_error, stats.event_driven.contact_solve_cpu_seconds);
  }
  if (scene.options.integrator.method == mbs::OdeMethod::kImplicit) {
    fmt::print("newton          {} iterations, {} setups, {} solve\n", stats.integrator.newton_iterations,
               stats.integrator.newton_setups, NewtonUsed(stats.integrator));
  }
  for (const mbs::ContactModeAdvice& a : advice) fmt::print("modes           {}\n", a.Describe());
  fmt::print("energy          {:.9g} J -> {:.9g} J\n", energy_start, energy_end);
  fmt::print("time            {:.3f} s for {:g} s simulated (real-time factor {:.3g})\n", stats.wall_seconds, simulated,
             stats.wall_seconds / simulated);
}

/// The run's report on stdout, as JSON (--json) or as text.
void Report(const SimulateOptions& options, const mbs::Scene& scene, const mbs::SimulationStatistics& stats,
            const std::vector<mbs::ContactModeAdvice>& advice, double energy_start, double energy_end) {
  if (options.json) {
    fmt::print("{}\n", ReportJson(options, scene, stats, advice, energy_start, energy_end).dump(2));
  } else {
    PrintReportText(options, scene, stats, advice, energy_start, energy_end);
  }
}

/// Wall-clock and process CPU time since it was made, summed into a part of the run's times.
class PartClock {
 public:
  PartClock() : wall_(std::chrono::steady_clock::now()), cpu_(std::clock()) {}
  /// Adds the time since construction to `part`.
  void AddTo(mbs::PartTime& part) const {
    part.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count();
    part.cpu_seconds += static_cast<double>(std::clock() - cpu_) / CLOCKS_PER_SEC;
  }

 private:
  std::chrono::steady_clock::time_point wall_;
  std::clock_t cpu_;
};

void RunSimulate(const SimulateOptions& options) {
  const PartClock setup_clock;
  mbs::RunTimes times;
  CheckOutputFolder("-o", options.output);
  const mbs::Scene scene = mbs::LoadScene(options.scene_file, SimulateSceneHooks());
  // Checked (and projected if slightly off) before the results file exists, so a refused
  // initial state leaves no file.
  Eigen::VectorXd y0 = scene.initial_state;
  mbs::ConsistencyReport initial;
  try {
    initial = mbs::MakeConsistent(*scene.system, scene.options.start_time, y0, scene.options.initial_conditions);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", options.scene_file, e.what()));
  }
  const std::vector<mbs::ContactModeAdvice> advice = mbs::AdviseContactModes(*scene.system, y0);
  mbs::ResultsWriter writer(options.output, Layout(scene, initial));
  std::optional<mbs::ParaviewWriter> paraview;
  if (scene.paraview.enabled) {
    paraview.emplace(*scene.system, mbs::ParaviewCollectionFor(options.output), scene.paraview.every);
  }
  Progress progress;
  double energy_start = std::nan(""), energy_end = std::nan("");
  const double end_time = scene.options.end_time;
  mbs::MoreauJeanStepReport contacts;  // the output interval that ended at the output time
  auto record_contacts = [&](double, const mbs::MoreauJeanStepReport& step) { contacts = step; };
  auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& lambda) {
    const PartClock output_clock;
    const mbs::ResultsSample sample = Sample(scene, t, y, lambda, contacts);
    if (std::isnan(energy_start)) energy_start = sample.kinetic_energy + sample.potential_energy;
    energy_end = sample.kinetic_energy + sample.potential_energy;
    writer.Append(sample);
    if (paraview) paraview->Record(t, y, contacts);
    progress.Show(fmt::format("t = {:.6g} s of {:g} s", t, end_time));
    output_clock.AddTo(times.output);
  };
  auto record_event = [&](const mbs::ContactEvent& event) {
    const PartClock output_clock;
    writer.AppendEvent(event);
    output_clock.AddTo(times.output);
  };
  setup_clock.AddTo(times.setup);
  // The integration's time is the Simulate call's less the output inside it.
  const PartClock run_clock;
  auto finish = [&](std::string_view termination, bool complete) {
    run_clock.AddTo(times.integration);
    times.integration.wall_seconds -= times.output.wall_seconds;
    times.integration.cpu_seconds -= times.output.cpu_seconds;
    writer.WriteStatistics(times);
    writer.Finish(termination, complete);
  };
  mbs::SimulationStatistics stats;
  try {
    stats = mbs::Simulate(*scene.system, scene.options, y0, record, record_contacts, record_event);
  } catch (const mbs::SimulationError& e) {
    progress.Clear();
    finish(e.what(), false);
    throw;
  }
  progress.Clear();
  times.contact_solve_cpu_seconds =
      stats.moreau_jean.contact_solve_cpu_seconds + stats.event_driven.contact_solve_cpu_seconds;
  finish("end time reached", true);
  stats.initial_conditions = initial;
  Report(options, scene, stats, advice, energy_start, energy_end);
}

}  // namespace

void AddSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand("simulate", "Integrate a scene of rigid and reduced flexible bodies and write its results");
  cmd->add_option("scene", options->scene_file, "Scene file (YAML, docs/scene.md)")->required();
  cmd->add_option("-o,--output", options->output, "The results file to write (.h5, docs/results.md)")->required();
  cmd->add_flag("--json", options->json, "Print the report as JSON (keys documented in docs/cli.md)");
  cmd->callback([options] { RunSimulate(*options); });
}

}  // namespace flexmbs::app
