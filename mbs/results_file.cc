#include "mbs/results_file.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <fmt/format.h>

#include "core/error.h"
#include "core/h5_file.h"
#include "core/version.h"

namespace flexmbs::mbs {
namespace {

/// The appendable datasets of one body.
struct BodySeries {
  h5::AppendableDataset position, orientation, velocity, angular_velocity;
  std::optional<h5::AppendableDataset> modal_coordinates, modal_velocities;
  std::vector<h5::AppendableDataset> markers;
};

struct JointSeries {
  h5::AppendableDataset force, torque;
};

struct ContactSeries {
  h5::AppendableDataset gap, normal_impulse, tangential_impulse, active, sliding;
};

/// The datasets of events/, one row per contact point and event.
struct EventSeries {
  h5::AppendableDataset time, kind, contact, point, normal_velocity_before, normal_velocity_after, normal_impulse,
      kinetic_energy_before, kinetic_energy_after, closed_after;
};

EventSeries CreateEvents(h5::Group& root) {
  h5::Group group = root.CreateGroup("events");
  group.SetStringAttribute("kind_values", "1 impact, 2 separation, 3 stick, 4 slip");
  return {group.CreateAppendable("time", {}, "s"),
          group.CreateAppendable("kind", {}, "1"),
          group.CreateAppendable("contact", {}, "1"),
          group.CreateAppendable("point", {}, "1"),
          group.CreateAppendable("normal_velocity_before", {}, "m/s"),
          group.CreateAppendable("normal_velocity_after", {}, "m/s"),
          group.CreateAppendable("normal_impulse", {}, "N s"),
          group.CreateAppendable("kinetic_energy_before", {}, "J"),
          group.CreateAppendable("kinetic_energy_after", {}, "J"),
          group.CreateAppendable("closed_after", {}, "1")};
}

}  // namespace

struct ResultsWriter::Impl {
  h5::File file;
  std::optional<h5::AppendableDataset> time, kinetic, potential, total, constraint_position, constraint_velocity;
  std::vector<BodySeries> bodies;
  std::vector<JointSeries> joints;
  std::vector<ContactSeries> contacts;
  std::vector<std::vector<h5::AppendableDataset>> element_series;  ///< per series, per channel
  std::vector<std::int64_t> element_widths;  ///< the channels' widths (0: scalar), flattened
  std::optional<EventSeries> events;
  std::chrono::steady_clock::time_point last_flush = std::chrono::steady_clock::now();
  double flush_interval_seconds = 1.0;
  bool finished = false;

  explicit Impl(h5::File f) : file(std::move(f)) {}

};

namespace {

BodySeries CreateBody(h5::Group& bodies, const ResultsLayout::Body& layout) {
  h5::Group group = bodies.CreateGroup(layout.name);
  group.SetStringAttribute("kind", layout.kind);
  BodySeries series{group.CreateAppendable("position", {3}, "m"), group.CreateAppendable("orientation", {4}, "1"),
                    group.CreateAppendable("velocity", {3}, "m/s"),
                    group.CreateAppendable("angular_velocity", {3}, "rad/s"), std::nullopt, std::nullopt, {}};
  if (!layout.mode_names.empty()) {
    const auto n = static_cast<std::int64_t>(layout.mode_names.size());
    group.WriteStrings("mode_names", layout.mode_names);
    series.modal_coordinates = group.CreateAppendable("modal_coordinates", {n}, "q");
    series.modal_velocities = group.CreateAppendable("modal_velocities", {n}, "q/s");
  }
  if (!layout.markers.empty()) {
    h5::Group markers = group.CreateGroup("markers");
    for (const std::string& marker : layout.markers) {
      series.markers.push_back(markers.CreateAppendable(marker, {3}, "m"));
    }
  }
  return series;
}

}  // namespace

ResultsWriter::ResultsWriter(const std::filesystem::path& path, const ResultsLayout& layout,
                             double flush_interval_seconds)
    : impl_(std::make_unique<Impl>(h5::File::Create(path, h5::WriteMode::kInPlace))) {
  impl_->flush_interval_seconds = flush_interval_seconds;
  h5::Group root = impl_->file.root();
  root.SetStringAttribute("format", kResultsFormat);
  root.SetIntegerAttribute("schema_version", kResultsSchemaVersion);
  root.SetIntegerAttribute("complete", 0);
  root.SetStringAttribute("termination", "interrupted");
  impl_->time = root.CreateAppendable("time", {}, "s");
  h5::Group energy = root.CreateGroup("energy");
  impl_->kinetic = energy.CreateAppendable("kinetic", {}, "J");
  impl_->potential = energy.CreateAppendable("potential", {}, "J");
  impl_->total = energy.CreateAppendable("total", {}, "J");
  h5::Group constraints = root.CreateGroup("constraints");
  impl_->constraint_position = constraints.CreateAppendable("position_residual", {}, "m or rad");
  impl_->constraint_velocity = constraints.CreateAppendable("velocity_residual", {}, "m/s or rad/s");
  h5::Group bodies = root.CreateGroup("bodies");
  for (const ResultsLayout::Body& body : layout.bodies) impl_->bodies.push_back(CreateBody(bodies, body));
  h5::Group joints = root.CreateGroup("joints");
  for (const ResultsLayout::Joint& joint : layout.joints) {
    h5::Group group = joints.CreateGroup(joint.name);
    group.SetStringAttribute("type", joint.type);
    impl_->joints.push_back({group.CreateAppendable("force", {3}, "N"), group.CreateAppendable("torque", {3}, "N m")});
  }
  if (!layout.contacts.empty()) {
    h5::Group contacts = root.CreateGroup("contacts");
    for (const ResultsLayout::Contact& contact : layout.contacts) {
      h5::Group group = contacts.CreateGroup(contact.name);
      group.SetStringAttribute("type", contact.type);
      impl_->contacts.push_back({group.CreateAppendable("gap", {}, "m"), group.CreateAppendable("normal_impulse", {}, "N s"),
                                 group.CreateAppendable("tangential_impulse", {2}, "N s"),
                                 group.CreateAppendable("active", {}, "1"),
                                 group.CreateAppendable("sliding", {}, "1")});
    }
  }
  std::map<std::string, h5::Group> folders;
  for (const ResultsLayout::ElementSeries& series : layout.element_series) {
    auto folder = folders.find(series.folder);
    if (folder == folders.end()) folder = folders.emplace(series.folder, root.CreateGroup(series.folder)).first;
    h5::Group group = folder->second.CreateGroup(series.name);
    group.SetStringAttribute("type", series.type);
    std::vector<h5::AppendableDataset> datasets;
    for (const ResultsLayout::ElementSeries::Channel& channel : series.channels) {
      std::vector<std::int64_t> row_shape;
      if (channel.width > 0) row_shape.push_back(channel.width);
      datasets.push_back(group.CreateAppendable(channel.name, row_shape, channel.unit));
      impl_->element_widths.push_back(channel.width);
    }
    impl_->element_series.push_back(std::move(datasets));
  }
  if (layout.events) impl_->events = CreateEvents(root);
  std::map<std::string, std::string> provenance = layout.provenance;
  provenance["tool_version"] = std::string(Version());
  std::vector<std::string> keys, values;
  for (const auto& [key, value] : provenance) {
    keys.push_back(key);
    values.push_back(value);
  }
  h5::Group group = root.CreateGroup("provenance");
  group.WriteStrings("keys", keys);
  group.WriteStrings("values", values);
  impl_->file.Flush();
}

ResultsWriter::~ResultsWriter() = default;

void ResultsWriter::Append(const ResultsSample& sample) {
  Impl& impl = *impl_;
  FLEXMBS_CHECK(!impl.finished, "results file already finished");
  FLEXMBS_CHECK(sample.positions.size() == impl.bodies.size() && sample.velocities.size() == impl.bodies.size() &&
                    sample.marker_positions.size() == impl.bodies.size() &&
                    sample.joint_forces.size() == impl.joints.size() &&
                    sample.joint_torques.size() == impl.joints.size() && sample.contacts.size() == impl.contacts.size(),
                "a results sample needs every body, joint and contact of the layout");
  // The element rows checked before anything is appended: a refused sample leaves no rows.
  FLEXMBS_CHECK(sample.element_rows.size() == impl.element_series.size(),
                "a results sample needs every element series of the layout");
  for (std::size_t e = 0, channel = 0; e < impl.element_series.size(); ++e) {
    FLEXMBS_CHECK(sample.element_rows[e].size() == impl.element_series[e].size(),
                  "a results sample's element series differ from the layout");
    for (const Eigen::VectorXd& row : sample.element_rows[e]) {
      FLEXMBS_CHECK(row.size() == std::max<std::int64_t>(impl.element_widths[channel++], 1),
                    "a results sample's channel width differs from the layout");
    }
  }
  for (std::size_t b = 0; b < impl.bodies.size(); ++b) {
    BodySeries& series = impl.bodies[b];
    const Eigen::VectorXd& x = sample.positions[b];
    const Eigen::VectorXd& u = sample.velocities[b];
    const Eigen::Index n = x.size() - 7;
    FLEXMBS_CHECK(n >= 0 && u.size() == 6 + n && (n > 0) == series.modal_coordinates.has_value() &&
                      sample.marker_positions[b].size() == series.markers.size(),
                  "a results sample's body sizes differ from the layout");
    series.position.AppendRow(Eigen::VectorXd(x.head<3>()));
    series.orientation.AppendRow(Eigen::VectorXd(x.segment<4>(3)));
    series.velocity.AppendRow(Eigen::VectorXd(u.head<3>()));
    series.angular_velocity.AppendRow(Eigen::VectorXd(u.segment<3>(3)));
    if (n > 0) {
      series.modal_coordinates->AppendRow(Eigen::VectorXd(x.tail(n)));
      series.modal_velocities->AppendRow(Eigen::VectorXd(u.tail(n)));
    }
    for (std::size_t m = 0; m < series.markers.size(); ++m) {
      series.markers[m].AppendRow(Eigen::VectorXd(sample.marker_positions[b][m]));
    }
  }
  for (std::size_t j = 0; j < impl.joints.size(); ++j) {
    impl.joints[j].force.AppendRow(Eigen::VectorXd(sample.joint_forces[j]));
    impl.joints[j].torque.AppendRow(Eigen::VectorXd(sample.joint_torques[j]));
  }
  for (std::size_t c = 0; c < impl.contacts.size(); ++c) {
    const ResultsSample::ContactSample& contact = sample.contacts[c];
    impl.contacts[c].gap.AppendRow(contact.gap);
    impl.contacts[c].normal_impulse.AppendRow(contact.normal_impulse);
    impl.contacts[c].tangential_impulse.AppendRow(Eigen::VectorXd(contact.tangential_impulse));
    impl.contacts[c].active.AppendRow(contact.active ? 1.0 : 0.0);
    impl.contacts[c].sliding.AppendRow(contact.sliding ? 1.0 : 0.0);
  }
  std::size_t channel = 0;
  for (std::size_t e = 0; e < impl.element_series.size(); ++e) {
    for (std::size_t c = 0; c < impl.element_series[e].size(); ++c, ++channel) {
      const Eigen::VectorXd& row = sample.element_rows[e][c];
      if (impl.element_widths[channel] == 0) {
        impl.element_series[e][c].AppendRow(row(0));
      } else {
        impl.element_series[e][c].AppendRow(row);
      }
    }
  }
  impl.kinetic->AppendRow(sample.kinetic_energy);
  impl.potential->AppendRow(sample.potential_energy);
  impl.total->AppendRow(sample.kinetic_energy + sample.potential_energy);
  impl.constraint_position->AppendRow(sample.constraint_position);
  impl.constraint_velocity->AppendRow(sample.constraint_velocity);
  // Time last: a reader takes the length of /time as the number of complete samples.
  impl.time->AppendRow(sample.time);
  const double since_flush =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - impl.last_flush).count();
  if (since_flush >= impl.flush_interval_seconds) Flush();
}

void ResultsWriter::AppendEvent(const ContactEvent& event) {
  Impl& impl = *impl_;
  FLEXMBS_CHECK(!impl.finished && impl.events.has_value(), "results file without events, or already finished");
  EventSeries& series = *impl.events;
  // Time last, as in Append: its length counts the complete rows.
  series.kind.AppendRow(static_cast<double>(static_cast<int>(event.kind)));
  series.contact.AppendRow(static_cast<double>(event.contact));
  series.point.AppendRow(static_cast<double>(event.point));
  series.normal_velocity_before.AppendRow(event.normal_velocity_before);
  series.normal_velocity_after.AppendRow(event.normal_velocity_after);
  series.normal_impulse.AppendRow(event.normal_impulse);
  series.kinetic_energy_before.AppendRow(event.kinetic_energy_before);
  series.kinetic_energy_after.AppendRow(event.kinetic_energy_after);
  series.closed_after.AppendRow(event.closed_after ? 1.0 : 0.0);
  series.time.AppendRow(event.time);
  const double since_flush =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - impl.last_flush).count();
  if (since_flush >= impl.flush_interval_seconds) Flush();
}

void ResultsWriter::WriteStatistics(const RunTimes& times) {
  Impl& impl = *impl_;
  FLEXMBS_CHECK(!impl.finished && !impl.file.root().HasGroup("statistics"),
                "statistics written twice, or after the results file was finished");
  h5::Group group = impl.file.root().CreateGroup("statistics");
  const PartTime total{times.setup.wall_seconds + times.integration.wall_seconds + times.output.wall_seconds,
                       times.setup.cpu_seconds + times.integration.cpu_seconds + times.output.cpu_seconds};
  const PartTime parts[] = {times.setup, times.integration, times.output, total};
  Eigen::Vector4d wall, cpu;
  for (int k = 0; k < 4; ++k) {
    wall(k) = parts[k].wall_seconds;
    cpu(k) = parts[k].cpu_seconds;
  }
  group.WriteStrings("parts", {"setup", "integration", "output", "total"});
  group.WriteVector("wall_seconds", wall, "s");
  group.WriteVector("cpu_seconds", cpu, "s");
  group.WriteScalar("contact_solve_cpu_seconds", times.contact_solve_cpu_seconds, "s");
}

void ResultsWriter::Flush() {
  impl_->file.Flush();
  impl_->last_flush = std::chrono::steady_clock::now();
}

void ResultsWriter::Finish(std::string_view termination, bool complete) {
  Impl& impl = *impl_;
  FLEXMBS_CHECK(!impl.finished, "results file already finished");
  h5::Group root = impl.file.root();
  root.SetIntegerAttribute("complete", complete ? 1 : 0);
  root.SetStringAttribute("termination", termination);
  impl.finished = true;
  impl.file.Commit();
}

std::int64_t ResultsWriter::samples() const { return impl_->time->rows(); }

h5::VerifyReport VerifyResultsFile(const std::filesystem::path& path) {
  const h5::File file = h5::File::Open(path);
  const h5::Group root = file.root();
  const std::int64_t version = root.HasAttribute("schema_version") ? root.GetIntegerAttribute("schema_version") : 0;
  if (version == 1) {
    throw InputError(fmt::format("{}: results schema_version 1 was written by an earlier flexmbs, without checksums; "
                                 "write it again with `flexmbs simulate SCENE.yaml -o {}`",
                                 path.string(), path.string()));
  }
  if (!root.HasAttribute("format") || root.GetStringAttribute("format") != kResultsFormat ||
      version != kResultsSchemaVersion) {
    throw InputError(fmt::format("{}: not a flexmbs results file of schema_version {} (format '{}')", path.string(),
                                 kResultsSchemaVersion, kResultsFormat));
  }
  return root.VerifyAll();
}

}  // namespace flexmbs::mbs
