// VTK XML formats: "VTK File Formats", VTK User's Guide (Kitware), section "XML File Formats":
// PolyData with Points, Verts/Lines/Polys as connectivity + offsets (the end of each cell), its
// arrays in a base64 AppendedData section (each a header_type byte count and the values, encoded
// together; offsets count characters), the
// multiblock file (.vtm) of DataSet entries, and ParaView's data collection (.pvd) of DataSet
// entries with a timestep.
#include "mbs/paraview_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <iterator>
#include <ostream>
#include <regex>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

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

/// Whether `name` is <stem>_<k>.vtm, <stem>_<k>_<b>.vtp or <stem>_<k>_contacts.vtp (k, b digits),
/// or the temporary of one that a killed run left (TemporaryPathFor): a file of a run.
bool IsSampleFileName(const std::string& name, const std::string& stem) {
  static const std::regex kSample(R"((\d+\.vtm|\d+_(\d+|contacts)\.vtp)(\.tmp\.\d+)?)");
  const std::string prefix = stem + "_";
  return name.starts_with(prefix) && std::regex_match(name.substr(prefix.size()), kSample);
}

using Buffer = fmt::memory_buffer;

/// The XML part of a PolyData file and its appended data: per DataArray a UInt64 byte count and
/// the values in the file's byte order (little-endian, as the machines flexmbs runs on), base64
/// encoded together (as VTK's own writer does), at the character offset the DataArray names.
struct PolyDataBuffers {
  Buffer xml;
  std::string appended;
};

/// Appends `bytes` base64-encoded (RFC 4648 alphabet, '=' padding) to `out`.
void AppendBase64(const std::vector<unsigned char>& bytes, std::string& out) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t triple = 0;
    for (std::size_t k = 0; k < 3; ++k) triple = (triple << 8) | (k < n ? bytes[i + k] : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(triple >> (18 - 6 * k)) & 63u] : '=';
  }
}

/// A DataArray of `values` converted to `Stored` (VTK type `type`), appended.
template <typename Stored, typename Values>
void AppendArray(PolyDataBuffers& out, std::string_view type, std::string_view attributes, const Values& values) {
  static_assert(std::endian::native == std::endian::little, "the files declare LittleEndian");
  fmt::format_to(std::back_inserter(out.xml),
                 "        <DataArray type=\"{}\" {} format=\"appended\" offset=\"{}\"/>\n", type, attributes,
                 out.appended.size());
  std::vector<unsigned char> bytes;
  const auto append = [&](const auto& value) {
    const auto* first = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), first, first + sizeof(value));
  };
  append(static_cast<std::uint64_t>(sizeof(Stored) * std::size(values)));
  for (const auto& value : values) append(static_cast<Stored>(value));
  AppendBase64(bytes, out.appended);
}

/// A Verts, Lines or Polys section of cells given by their sizes and concatenated points.
void AppendCells(PolyDataBuffers& out, std::string_view section, const std::vector<int>& sizes,
                 const std::vector<int>& points) {
  if (sizes.empty()) return;
  std::vector<std::int32_t> offsets(sizes.size());
  std::int32_t end = 0;
  for (std::size_t c = 0; c < sizes.size(); ++c) offsets[c] = end += sizes[c];
  fmt::format_to(std::back_inserter(out.xml), "      <{}>\n", section);
  AppendArray<std::int32_t>(out, "Int32", "Name=\"connectivity\"", points);
  AppendArray<std::int32_t>(out, "Int32", "Name=\"offsets\"", offsets);
  fmt::format_to(std::back_inserter(out.xml), "      </{}>\n", section);
}

/// The columns of a 3 x N matrix as a flat list, x y z per column.
std::span<const double> Flat(const Eigen::Matrix3Xd& points) {
  return {points.data(), static_cast<std::size_t>(points.size())};
}

/// The one <Piece> of a body's PolyData file.
void AppendPiece(PolyDataBuffers& out, const BodyGeometry& body, int body_id) {
  const std::vector<int> vertex_sizes(body.vertex_points.size(), 1), line_sizes(body.line_points.size() / 2, 2);
  fmt::format_to(std::back_inserter(out.xml),
                 "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
                 "NumberOfPolys=\"{}\">\n",
                 body.p_WP_W.cols(), vertex_sizes.size(), line_sizes.size(), body.polygon_sizes.size());
  fmt::format_to(std::back_inserter(out.xml),
                 "      <PointData Vectors=\"displacement\" Scalars=\"displacement_magnitude\">\n");
  AppendArray<double>(out, "Float64", "Name=\"displacement\" NumberOfComponents=\"3\"", Flat(body.u_P_W));
  const Eigen::VectorXd magnitude = body.u_P_W.colwise().norm().transpose();
  AppendArray<double>(out, "Float64", "Name=\"displacement_magnitude\"",
                      std::span<const double>(magnitude.data(), static_cast<std::size_t>(magnitude.size())));
  fmt::format_to(std::back_inserter(out.xml), "      </PointData>\n      <CellData Scalars=\"body_id\">\n");
  AppendArray<std::int32_t>(out, "Int32", "Name=\"body_id\"",
                            std::vector<int>(static_cast<std::size_t>(body.num_cells()), body_id));
  fmt::format_to(std::back_inserter(out.xml), "      </CellData>\n      <Points>\n");
  AppendArray<double>(out, "Float64", "Name=\"Points\" NumberOfComponents=\"3\"", Flat(body.p_WP_W));
  fmt::format_to(std::back_inserter(out.xml), "      </Points>\n");
  AppendCells(out, "Verts", vertex_sizes, body.vertex_points);
  AppendCells(out, "Lines", line_sizes, body.line_points);
  AppendCells(out, "Polys", body.polygon_sizes, body.polygon_points);
  fmt::format_to(std::back_inserter(out.xml), "    </Piece>\n");
}

/// The one <Piece> of a contacts PolyData file: a vertex per load.
void AppendContactPiece(PolyDataBuffers& out, const std::vector<ContactLoad>& loads) {
  const std::size_t n = loads.size();
  Eigen::Matrix3Xd p_W(3, static_cast<Eigen::Index>(n)), f_W(3, static_cast<Eigen::Index>(n)),
      n_W(3, static_cast<Eigen::Index>(n));
  std::vector<double> normal_force(n);
  std::vector<int> contact_id(n), vertices(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Index c = static_cast<Eigen::Index>(i);
    p_W.col(c) = loads[i].p_W;
    f_W.col(c) = loads[i].f_W;
    n_W.col(c) = loads[i].n_W;
    normal_force[i] = loads[i].f_W.dot(loads[i].n_W);
    contact_id[i] = loads[i].contact_id;
    vertices[i] = static_cast<int>(i);
  }
  fmt::format_to(std::back_inserter(out.xml),
                 "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                 "NumberOfPolys=\"0\">\n      <PointData Vectors=\"force\" Scalars=\"normal_force\">\n",
                 n, n);
  AppendArray<double>(out, "Float64", "Name=\"force\" NumberOfComponents=\"3\"", Flat(f_W));
  AppendArray<double>(out, "Float64", "Name=\"normal\" NumberOfComponents=\"3\"", Flat(n_W));
  AppendArray<double>(out, "Float64", "Name=\"normal_force\"", normal_force);
  AppendArray<std::int32_t>(out, "Int32", "Name=\"contact_id\"", contact_id);
  fmt::format_to(std::back_inserter(out.xml), "      </PointData>\n      <Points>\n");
  AppendArray<double>(out, "Float64", "Name=\"Points\" NumberOfComponents=\"3\"", Flat(p_W));
  fmt::format_to(std::back_inserter(out.xml), "      </Points>\n");
  AppendCells(out, "Verts", std::vector<int>(n, 1), vertices);
  fmt::format_to(std::back_inserter(out.xml), "    </Piece>\n");
}

/// Writes a PolyData file whose one piece `append_piece` adds.
template <typename AppendPieceTo>
void WritePolyDataFile(std::ostream& out, AppendPieceTo append_piece) {
  PolyDataBuffers buffers;
  fmt::format_to(std::back_inserter(buffers.xml),
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\">\n  <PolyData>\n");
  append_piece(buffers);
  fmt::format_to(std::back_inserter(buffers.xml), "  </PolyData>\n  <AppendedData encoding=\"base64\">\n   _");
  out.write(buffers.xml.data(), static_cast<std::streamsize>(buffers.xml.size()));
  out << buffers.appended << "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace

fs::path ParaviewCollectionFor(const fs::path& results) {
  return results.parent_path() / (results.stem().string() + ".pvd");
}

void WritePolyData(std::ostream& out, const BodyGeometry& body, int body_id) {
  WritePolyDataFile(out, [&](PolyDataBuffers& buffers) { AppendPiece(buffers, body, body_id); });
}

void WriteContactPolyData(std::ostream& out, const std::vector<ContactLoad>& loads) {
  WritePolyDataFile(out, [&](PolyDataBuffers& buffers) { AppendContactPiece(buffers, loads); });
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
  draws_contacts_ = system_.num_unilateral_contacts() > 0;
  for (int i = 0; i < system_.num_force_elements(); ++i) draws_contacts_ |= system_.force_element(i).is_contact();
  WriteCollection();
}

fs::path ParaviewWriter::SampleFile(long k) const { return folder_ / fmt::format("{}_{:06d}.vtm", stem_, k); }

fs::path ParaviewWriter::BodyFile(long k, int b) const {
  return folder_ / fmt::format("{}_{:06d}_{}.vtp", stem_, k, b);
}

fs::path ParaviewWriter::ContactFile(long k) const { return folder_ / fmt::format("{}_{:06d}_contacts.vtp", stem_, k); }

std::vector<ContactLoad> ParaviewWriter::ContactLoads(double t, const ConstVectorRef& y,
                                                      const MoreauJeanStepReport& contacts) const {
  std::vector<ContactLoad> loads;
  for (std::size_t k = 0; k < contacts.contacts.size(); ++k) {
    for (ContactLoad load : contacts.contacts[k].loads) {
      load.contact_id = static_cast<int>(k);
      loads.push_back(load);
    }
  }
  for (int i = 0; i < system_.num_force_elements(); ++i) {
    for (ContactLoad load : system_.force_element(i).ContactLoads(t, system_, y)) {
      load.contact_id = system_.num_unilateral_contacts() + i;
      loads.push_back(load);
    }
  }
  return loads;
}

bool ParaviewWriter::Record(double t, const ConstVectorRef& y, const MoreauJeanStepReport& contacts) {
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
  if (draws_contacts_) {
    const std::vector<ContactLoad> loads = ContactLoads(t, y, contacts);
    WriteFileAtomically(ContactFile(k), [&](std::ostream& out) { WriteContactPolyData(out, loads); });
    fmt::format_to(std::back_inserter(blocks), "    <DataSet index=\"{}\" name=\"contacts\" file=\"{}\"/>\n",
                   system_.num_bodies(), XmlEscaped(ContactFile(k).filename().string()));
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
