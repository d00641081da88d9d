// VTK XML formats: "VTK File Formats", VTK User's Guide (Kitware), section "XML File Formats":
// PolyData with Points, Verts/Lines/Polys as connectivity + offsets (the end of each cell), the
// multiblock file (.vtm) of DataSet entries, and ParaView's data collection (.pvd) of DataSet
// entries with a timestep.
#include "mbs/paraview_writer.h"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <ostream>
#include <regex>
#include <span>
#include <string_view>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;

/// `text` with the characters XML attributes cannot hold as entities.
std::string XmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// Whether `name` is <stem>_<k>.vtm or <stem>_<k>_<b>.vtp (k, b digits), or the temporary of
/// one that a killed run left (TemporaryPathFor): a file of a run.
bool IsSampleFileName(const std::string& name, const std::string& stem) {
  static const std::regex kSample(R"((\d+\.vtm|\d+_\d+\.vtp)(\.tmp\.\d+)?)");
  const std::string prefix = stem + "_";
  return name.starts_with(prefix) && std::regex_match(name.substr(prefix.size()), kSample);
}

using Buffer = fmt::memory_buffer;

/// An ascii DataArray of `values` (numbers separated by spaces; doubles in their shortest form
/// that reads back exactly).
template <typename Values>
void AppendArray(Buffer& out, std::string_view attributes, const Values& values) {
  fmt::format_to(std::back_inserter(out), "        <DataArray {} format=\"ascii\">\n", attributes);
  for (const auto& value : values) fmt::format_to(std::back_inserter(out), FMT_COMPILE("{} "), value);
  fmt::format_to(std::back_inserter(out), "\n        </DataArray>\n");
}

/// A Verts, Lines or Polys section of cells given by their sizes and concatenated points.
void AppendCells(Buffer& out, std::string_view section, const std::vector<int>& sizes, const std::vector<int>& points) {
  if (sizes.empty()) return;
  std::vector<long> offsets(sizes.size());
  long end = 0;
  for (std::size_t c = 0; c < sizes.size(); ++c) offsets[c] = end += sizes[c];
  fmt::format_to(std::back_inserter(out), "      <{}>\n", section);
  AppendArray(out, "type=\"Int64\" Name=\"connectivity\"", points);
  AppendArray(out, "type=\"Int64\" Name=\"offsets\"", offsets);
  fmt::format_to(std::back_inserter(out), "      </{}>\n", section);
}

/// The columns of a 3 x N matrix as a flat list, x y z per column.
std::span<const double> Flat(const Eigen::Matrix3Xd& points) {
  return {points.data(), static_cast<std::size_t>(points.size())};
}

/// The one <Piece> of a body's PolyData file.
void AppendPiece(Buffer& out, const BodyGeometry& body, int body_id) {
  const std::vector<int> vertex_sizes(body.vertex_points.size(), 1), line_sizes(body.line_points.size() / 2, 2);
  fmt::format_to(std::back_inserter(out),
                 "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
                 "NumberOfPolys=\"{}\">\n",
                 body.p_WP_W.cols(), vertex_sizes.size(), line_sizes.size(), body.polygon_sizes.size());
  fmt::format_to(std::back_inserter(out),
                 "      <PointData Vectors=\"displacement\" Scalars=\"displacement_magnitude\">\n");
  AppendArray(out, "type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"", Flat(body.u_P_W));
  const Eigen::VectorXd magnitude = body.u_P_W.colwise().norm().transpose();
  AppendArray(out, "type=\"Float64\" Name=\"displacement_magnitude\"",
              std::span<const double>(magnitude.data(), static_cast<std::size_t>(magnitude.size())));
  fmt::format_to(std::back_inserter(out), "      </PointData>\n      <CellData Scalars=\"body_id\">\n");
  AppendArray(out, "type=\"Int32\" Name=\"body_id\"", std::vector<int>(static_cast<std::size_t>(body.num_cells()), body_id));
  fmt::format_to(std::back_inserter(out), "      </CellData>\n      <Points>\n");
  AppendArray(out, "type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"", Flat(body.p_WP_W));
  fmt::format_to(std::back_inserter(out), "      </Points>\n");
  AppendCells(out, "Verts", vertex_sizes, body.vertex_points);
  AppendCells(out, "Lines", line_sizes, body.line_points);
  AppendCells(out, "Polys", body.polygon_sizes, body.polygon_points);
  fmt::format_to(std::back_inserter(out), "    </Piece>\n");
}

}  // namespace

fs::path ParaviewCollectionFor(const fs::path& results) {
  return results.parent_path() / (results.stem().string() + ".pvd");
}

void WritePolyData(std::ostream& out, const BodyGeometry& body, int body_id) {
  Buffer buffer;
  fmt::format_to(std::back_inserter(buffer),
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                 "  <PolyData>\n");
  AppendPiece(buffer, body, body_id);
  fmt::format_to(std::back_inserter(buffer), "  </PolyData>\n</VTKFile>\n");
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

ParaviewWriter::ParaviewWriter(const MultibodySystem& system, const fs::path& collection, int every)
    : system_(system),
      collection_(collection),
      folder_(collection.parent_path() / (collection.stem().string() + "_vtk")),
      stem_(collection.stem().string()),
      every_(every) {
  FLEXMBS_CHECK(every >= 1, "ParaView output of every n-th sample, n >= 1");
  std::error_code error;
  fs::create_directories(folder_, error);
  if (error || !fs::is_directory(folder_)) {
    throw InputError(fmt::format("{}: cannot create the folder for the ParaView files: {}", folder_.string(),
                                 error ? error.message() : "not a folder"));
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_)) {
    if (entry.is_regular_file() && IsSampleFileName(entry.path().filename().string(), stem_)) {
      fs::remove(entry.path(), error);
    }
  }
  for (int b = 0; b < system_.num_bodies(); ++b) drawings_.emplace_back(system_.body(b));
  WriteCollection();
}

fs::path ParaviewWriter::SampleFile(long k) const { return folder_ / fmt::format("{}_{:06d}.vtm", stem_, k); }

fs::path ParaviewWriter::BodyFile(long k, int b) const {
  return folder_ / fmt::format("{}_{:06d}_{}.vtp", stem_, k, b);
}

bool ParaviewWriter::Record(double t, const ConstVectorRef& y) {
  const bool write = offered_ % every_ == 0;
  ++offered_;
  if (!write) return false;
  const long k = samples();
  Buffer blocks;
  fmt::format_to(std::back_inserter(blocks),
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
                 "byte_order=\"LittleEndian\">\n  <vtkMultiBlockDataSet>\n");
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const BodyGeometry geometry = drawings_[static_cast<std::size_t>(b)].At(system_.BodyPositions(y, b));
    WriteFileAtomically(BodyFile(k, b), [&](std::ostream& out) { WritePolyData(out, geometry, b); });
    fmt::format_to(std::back_inserter(blocks), "    <DataSet index=\"{}\" name=\"{}\" file=\"{}\"/>\n", b,
                   XmlEscaped(system_.body(b).name()), XmlEscaped(BodyFile(k, b).filename().string()));
  }
  fmt::format_to(std::back_inserter(blocks), "  </vtkMultiBlockDataSet>\n</VTKFile>\n");
  WriteFileAtomically(SampleFile(k), [&](std::ostream& out) {
    out.write(blocks.data(), static_cast<std::streamsize>(blocks.size()));
  });
  const fs::path relative = folder_.filename() / SampleFile(k).filename();
  collection_entries_ += fmt::format("    <DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>\n", t,
                                     XmlEscaped(relative.generic_string()));
  ++samples_;
  WriteCollection();
  return true;
}

void ParaviewWriter::WriteCollection() const {
  WriteFileAtomically(collection_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
           "  <Collection>\n"
        << collection_entries_ << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace flexmbs::mbs
