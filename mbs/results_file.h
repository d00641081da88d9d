#pragma once
// The results file of `flexmbs simulate` (layout: docs/results.md): time series of body
// states, marker positions, joint loads and energies, written while the simulation runs. The
// file is written in place and flushed at least every `flush_interval_seconds`, so a killed run
// leaves a readable file with every sample up to the last flush; the root attribute `complete`
// is 0 until Finish.

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/h5_file.h"
#include "mbs/event_driven.h"

namespace flexmbs::mbs {

/// The results file's format attribute and schema version (2: every dataset checksummed with
/// Fletcher32, fixed-length strings; schema 1 had neither).
inline constexpr std::string_view kResultsFormat = "flexmbs-results";
inline constexpr int kResultsSchemaVersion = 2;

/// Reads a results file in full (h5::Group::VerifyAll) after checking its format and schema:
/// what `flexmbs info --verify` checks. Throws InputError naming `path` at the first problem;
/// a file of schema 1 is refused with the command that writes it again.
h5::VerifyReport VerifyResultsFile(const std::filesystem::path& path);

/// What the file records, fixed when it is created.
struct ResultsLayout {
  struct Body {
    std::string name;
    std::string kind;                     ///< "rigid" or "flexible"
    std::vector<std::string> mode_names;  ///< the kept modes (empty for rigid bodies)
    std::vector<std::string> markers;     ///< markers whose positions are recorded
  };
  struct Joint {
    std::string name;
    std::string type;  ///< "revolute", ...
  };
  /// A unilateral contact (Moreau-Jean runs).
  struct Contact {
    std::string name;
    std::string type;  ///< "sphere_plane", "sphere_sphere"
  };
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<Contact> contacts;
  /// A force element's own time series (a spur gear's mesh: app/gear_results.h), written as the
  /// group <folder>/<name>/ with the attribute `type` and one dataset per channel. The writer
  /// knows no element types: the caller names the channels and fills their rows.
  struct ElementSeries {
    std::string folder;  ///< the group they sit in, e.g. "gears"
    std::string name;    ///< the force element's name
    std::string type;    ///< its scene type, e.g. "spur_gear_contact"
    struct Channel {
      std::string name;
      std::int64_t width = 0;  ///< values per row; 0: one value (an N series)
      std::string unit;
    };
    std::vector<Channel> channels;
  };
  std::vector<ElementSeries> element_series;
  /// Event-driven runs: the group events/ with one row per contact point at each event
  /// (ResultsWriter::AppendEvent).
  bool events = false;
  /// Scene file, integrator, tolerances, tool version, ...: written as /provenance.
  std::map<std::string, std::string> provenance;
};

/// One output time: per body its positions x_b = [p_WBo_W, e, q] and velocities
/// u_b = [v_WBo_W, w_WB_B, qdot] (docs/mbs.md), marker positions p_WM_W per body and marker,
/// joint loads per joint (force [N] and torque [N m] on the second body at its marker, in W),
/// energies [J], and per unilateral contact the output interval that ended at this time
/// (ContactSample).
struct ResultsSample {
  double time = 0.0;
  std::vector<Eigen::VectorXd> positions;
  std::vector<Eigen::VectorXd> velocities;
  std::vector<std::vector<Eigen::Vector3d>> marker_positions;
  std::vector<Eigen::Vector3d> joint_forces;
  std::vector<Eigen::Vector3d> joint_torques;
  double kinetic_energy = 0.0;
  double potential_energy = 0.0;
  /// The constraints' drift: max |g_k| over the kept rows [m for translations, 1 (about rad) for
  /// rotations] and max |(G u + g_t)_k| [m/s, rad/s] (MeasureConstraints); 0 without joints.
  double constraint_position = 0.0;
  double constraint_velocity = 0.0;
  /// One unilateral contact at an output time: its gap [m], the impulses [N s] summed over the
  /// Moreau-Jean steps since the last output, and whether it was active in any of them
  /// (mbs/moreau_jean_simulation.h).
  struct ContactSample {
    double gap = 0.0;
    double normal_impulse = 0.0;
    Eigen::Vector2d tangential_impulse = Eigen::Vector2d::Zero();  ///< along t1_W, t2_W
    bool active = false;
    bool sliding = false;  ///< a point slid in any of those steps (ContactStepResult::sliding)
  };
  std::vector<ContactSample> contacts;
  /// Per ResultsLayout::ElementSeries, per channel its row (max(width, 1) values).
  std::vector<std::vector<Eigen::VectorXd>> element_rows;
};

/// Wall-clock and CPU (process) seconds of one part of a run.
struct PartTime {
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
};

/// Where a run's time went, written as statistics/ (ResultsWriter::WriteStatistics): the setup
/// (scene, initial state, results file), the integration (the integrator with its contact solves
/// and events, output excluded) and the output (samples, events, ParaView frames); of the
/// integration's CPU time the contact solves' share (MoreauJeanStatistics, EventDrivenStatistics:
/// contact_solve_cpu_seconds; 0 without unilateral contacts, NaN where not measured: a failed run).
struct RunTimes {
  PartTime setup, integration, output;
  double contact_solve_cpu_seconds = std::numeric_limits<double>::quiet_NaN();
};

/// Writes a results file sample by sample.
class ResultsWriter {
 public:
  /// Creates `path` (replacing an old file) with the datasets of `layout`. Throws InputError
  /// naming `path` if it cannot be created.
  ResultsWriter(const std::filesystem::path& path, const ResultsLayout& layout, double flush_interval_seconds = 1.0);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Appends one sample; flushes if the last flush is older than the interval. Precondition:
  /// the sample's sizes match the layout (InternalError otherwise).
  void Append(const ResultsSample& sample);
  /// Appends one contact point's event to events/ (time, kind, contact, point, normal velocities
  /// before and after, normal impulse, kinetic energies before and after, closed after);
  /// flushes as Append. Precondition: the layout has events (InternalError otherwise).
  void AppendEvent(const ContactEvent& event);
  /// Writes statistics/ (docs/results.md): `parts` (setup, integration, output, total), per part
  /// `wall_seconds` and `cpu_seconds`, and `contact_solve_cpu_seconds`. At most once, before
  /// Finish (InternalError otherwise).
  void WriteStatistics(const RunTimes& times);
  /// Writes everything so far to disk.
  void Flush();
  /// Records why the run ended (`termination`: "end time reached", "failed at t = ...") and
  /// whether it reached its end (`complete`), and closes the file.
  void Finish(std::string_view termination, bool complete = true);
  /// Samples written so far.
  std::int64_t samples() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexmbs::mbs
