// `flexmbs info`: a summary of a flexmbs file, or with --verify whether it is intact. The file's
// `format` attribute picks the summary and the check (kFileKinds): reduced bodies (`.sid.h5`) and,
// for --verify, results files.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "core/h5_file.h"
#include "core/polygon.h"
#include "mbs/results_file.h"
#include "reduction/modal_basis.h"
#include "sid/sid_file.h"

namespace flexmbs::app {
namespace {

namespace fs = std::filesystem;

struct InfoOptions {
  std::string file;
  bool json = false;
  bool verify = false;
};

// --- reduced bodies (`.sid.h5`) ----------------------------------------------------------------

/// The area of a contact surface [m^2]: the sum of its polygons' areas.
double SurfaceArea(const sid::ContactSurface& surface) {
  double area = 0.0;
  std::size_t first = 0;
  for (const int size : surface.face_sizes) {
    const auto count = static_cast<std::size_t>(size);
    area += PolygonAreaVector(surface.vertices, std::span<const int>(surface.face_vertices).subspan(first, count)).norm();
    first += count;
  }
  return area;
}

/// The number of modes of each kind; InputError for a kind flexmbs does not know.
reduction::ModeCounts CountModes(const fs::path& file, const sid::ReducedBody& body) {
  for (std::size_t k = 0; k < body.mode_kinds.size(); ++k) {
    if (!reduction::ModeKindFromName(body.mode_kinds[k])) {
      throw InputError(fmt::format("{}: /refmod/mode_kinds: mode '{}' has the unknown kind '{}'", file.string(),
                                   body.mode_names[k], body.mode_kinds[k]));
    }
  }
  auto count = [&body](reduction::ModeKind kind) -> Eigen::Index {
    return std::count(body.mode_kinds.begin(), body.mode_kinds.end(), reduction::ModeKindName(kind));
  };
  return {count(reduction::ModeKind::kRigid), count(reduction::ModeKind::kNormal),
          count(reduction::ModeKind::kConstraint), count(reduction::ModeKind::kStaticCorrection)};
}

std::string Vector3Text(const Eigen::Vector3d& v) { return fmt::format("[{:.6g}, {:.6g}, {:.6g}]", v(0), v(1), v(2)); }

void PrintBodyJson(const fs::path& file, const sid::ReducedBody& body, const reduction::ModeCounts& counts) {
  nlohmann::json j;
  j["file"] = file.string();
  j["format"] = sid::kSidFormat;
  j["schema_version"] = sid::ReadSidSchemaVersion(file);
  j["name"] = body.name;
  j["mass_kg"] = body.mass;
  j["center_of_mass_m"] = ToJson(body.center_of_mass);
  j["inertia_about_com_kg_m2"] = ToJson(body.inertia_about_center_of_mass);
  j["fe_nodes"] = body.node_positions.cols();
  j["modes"] = {{"rigid", counts.rigid}, {"normal", counts.normal}, {"constraint", counts.constraint},
                {"static_correction", counts.static_correction}, {"total", counts.total()}};
  j["mode_names"] = body.mode_names;
  j["mode_kinds"] = body.mode_kinds;
  j["frequency_hz"] = ToJson(body.frequency_hz);
  j["damping"] = body.damping;
  nlohmann::json nodes = nlohmann::json::array();
  for (const sid::Node& node : body.nodes) {
    nodes.push_back({{"name", node.name}, {"coupling", node.coupling}, {"fe_nodes", node.fe_nodes.size()},
                     {"position_m", ToJson(node.origin.m0)}});
  }
  j["nodes"] = nodes;
  nlohmann::json surfaces = nlohmann::json::array();
  for (const sid::ContactSurface& surface : body.surfaces) {
    surfaces.push_back({{"name", surface.name}, {"vertices", surface.vertices.rows()},
                        {"faces", surface.face_sizes.size()}, {"area_m2", SurfaceArea(surface)}});
  }
  j["surfaces"] = surfaces;
  j["visual_surface_faces"] = body.visual_surface.face_sizes.size();
  j["stiffening"] = !body.stiffening.empty();
  j["provenance"] = body.provenance;
  fmt::print("{}\n", j.dump(2));
}

void PrintBodyText(const fs::path& file, const sid::ReducedBody& body, const reduction::ModeCounts& counts) {
  const Eigen::Matrix3d& I = body.inertia_about_center_of_mass;
  fmt::print("file            {} ({} schema {})\n", file.string(), sid::kSidFormat, sid::ReadSidSchemaVersion(file));
  fmt::print("body            {}\n", body.name);
  fmt::print("mass            {:.6g} kg\n", body.mass);
  fmt::print("centre of mass  {} m\n", Vector3Text(body.center_of_mass));
  fmt::print("inertia at CoM  [{:.6g}, {:.6g}, {:.6g}; {:.6g}, {:.6g}, {:.6g}; {:.6g}, {:.6g}, {:.6g}] kg m^2\n",
             I(0, 0), I(0, 1), I(0, 2), I(1, 0), I(1, 1), I(1, 2), I(2, 0), I(2, 1), I(2, 2));
  fmt::print("FE nodes        {}\n", body.node_positions.cols());
  fmt::print("modes           {} ({} in all)\n", reduction::FormatModeCounts(counts), counts.total());
  for (Eigen::Index k = 0; k < body.num_modes(); ++k) {
    const auto m = static_cast<std::size_t>(k);
    const double f = body.frequency_hz(k);
    fmt::print("  {:>3}  {:<28} {:<18} {}\n", k + 1, body.mode_names[m], body.mode_kinds[m],
               std::isnan(f) ? std::string("-") : fmt::format("{:.6g} Hz", f));
  }
  fmt::print("damping         {}\n", body.damping);
  fmt::print("nodes           {}\n", body.nodes.size());
  for (const sid::Node& node : body.nodes) {
    fmt::print("  {:<20} {} coupling, {} FE nodes, at {} m\n", node.name, node.coupling, node.fe_nodes.size(),
               Vector3Text(node.origin.m0));
  }
  fmt::print("visual surface  {} faces\n", body.visual_surface.face_sizes.size());
  fmt::print("surfaces        {}\n", body.surfaces.size());
  for (const sid::ContactSurface& surface : body.surfaces) {
    fmt::print("  {:<20} {} vertices, {} faces, {:.6g} m^2\n", surface.name, surface.vertices.rows(),
               surface.face_sizes.size(), SurfaceArea(surface));
  }
  fmt::print("stiffening      {}\n", body.stiffening.empty() ? "no" : "yes");
  fmt::print("provenance\n");
  std::size_t key_width = 0;
  for (const auto& [key, value] : body.provenance) key_width = std::max(key_width, key.size());
  for (const auto& [key, value] : body.provenance) fmt::print("  {:<{}}  {}\n", key, key_width, value);
}

void ReportBody(const fs::path& file, bool json) {
  const sid::ReducedBody body = sid::ReadReducedBody(file);
  const reduction::ModeCounts counts = CountModes(file, body);
  if (json) {
    PrintBodyJson(file, body, counts);
  } else {
    PrintBodyText(file, body, counts);
  }
}

// --- dispatch ----------------------------------------------------------------------------------

// --- verification ------------------------------------------------------------------------------

/// Prints that `file` (of `format`) is intact and what was read: one line, or JSON.
void PrintIntact(const fs::path& file, std::string_view format, const h5::VerifyReport& report, bool json) {
  if (json) {
    const nlohmann::json j{{"file", file.string()},          {"format", format},
                           {"intact", true},                 {"groups", report.groups},
                           {"datasets", report.datasets},    {"attributes", report.attributes},
                           {"values", report.values},        {"content_sha256", report.content_sha256}};
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("{}: intact ({}; {} groups, {} datasets, {} attributes, {} values read; every checksum holds{})\n",
             file.string(), format, report.groups, report.datasets, report.attributes, report.values,
             format == sid::kSidFormat ? "; content digest holds" : "");
}

// --- dispatch ----------------------------------------------------------------------------------

/// A kind of file `flexmbs info` reads: the root `format` attribute that marks it, its summary
/// (text, or JSON with `json`; none for results files) and its full check (--verify).
struct FileKind {
  std::string_view format;
  void (*report)(const fs::path& file, bool json);
  h5::VerifyReport (*verify)(const fs::path& file);
};

constexpr std::array<FileKind, 2> kFileKinds{{{sid::kSidFormat, &ReportBody, &sid::VerifyReducedBodyFile},
                                              {mbs::kResultsFormat, nullptr, &mbs::VerifyResultsFile}}};

/// The root `format` attribute of `file` ("" if it has none). Throws InputError for a missing,
/// non-HDF5 or corrupt file.
std::string FileFormat(const fs::path& file) {
  const h5::File h5 = h5::File::Open(file);
  const h5::Group root = h5.root();
  return root.HasAttribute("format") ? root.GetStringAttribute("format") : std::string();
}

void RunInfo(const InfoOptions& options) {
  const std::string format = FileFormat(options.file);
  std::string known;
  for (const FileKind& kind : kFileKinds) {
    if (kind.format == format && options.verify) {
      PrintIntact(options.file, format, kind.verify(options.file), options.json);
      return;
    }
    if (kind.format == format && kind.report != nullptr) {
      kind.report(options.file, options.json);
      return;
    }
    if (kind.report != nullptr) known += fmt::format("{}{}", known.empty() ? "" : ", ", kind.format);
  }
  throw InputError(fmt::format("{}: not a file flexmbs info reads ({}; it reads: {}; with --verify also {})",
                               options.file,
                               format.empty() ? std::string("no 'format' attribute") : fmt::format("format '{}'", format),
                               known, mbs::kResultsFormat));
}

}  // namespace

void AddInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Summarise a flexmbs file: a reduced body (.sid.h5): mass, modes, nodes, surfaces, provenance; "
              "or with --verify check that a body or results file is intact");
  cmd->add_option("file", options->file, "The file (.sid.h5, or results .h5 with --verify)")->required();
  cmd->add_flag("--json", options->json, "Print the summary as JSON (keys documented in docs/cli.md)");
  cmd->add_flag("--verify", options->verify,
                "Read every value of the file (.sid.h5 or results) and check its checksums and content digest: "
                "exit 0 if intact, else a one-line error and exit 2");
  cmd->callback([options] { RunInfo(*options); });
}

}  // namespace flexmbs::app
