// The `.sid.h5` file: exact round trip of every field, units on every numeric dataset, and
// one-line errors for foreign, truncated, wrong-version, mislabelled and inconsistent files.
#include "sid/sid_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "core/h5_file.h"
#include "sid/sid_digest.h"
#include "tests/sid/sample_body.h"
#include "tests/input_error.h"

namespace flexmbs::sid {
namespace {

namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("flexmbs_sid_file_test_{}", getpid());
  fs::create_directories(dir);
  return dir / name;
}

constexpr Eigen::Index kModes = testing::kSampleModes;
constexpr Eigen::Index kNodes = testing::kSampleNodes;
using testing::SampleBody;

// Equal matrices, NaN where the other has NaN (HDF5 stores doubles unchanged).
void ExpectSame(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  EXPECT_TRUE(((a.array() == b.array()) || (a.array().isNaN() && b.array().isNaN())).all());
}

TEST(SidFile, RoundTripIsExact) {
  const fs::path path = TempPath("round_trip.sid.h5");
  const ReducedBody written = SampleBody();
  WriteReducedBody(path, written);
  const ReducedBody read = ReadReducedBody(path);
  EXPECT_EQ(read.name, written.name);
  EXPECT_EQ(read.mass, written.mass);
  ExpectSame(read.center_of_mass, written.center_of_mass);
  ExpectSame(read.inertia_about_center_of_mass, written.inertia_about_center_of_mass);
  EXPECT_EQ(read.mode_names, written.mode_names);
  EXPECT_EQ(read.mode_kinds, written.mode_kinds);
  ExpectSame(read.frequency_hz, written.frequency_hz);
  ExpectSame(read.relative_residuals, written.relative_residuals);
  EXPECT_EQ(read.damping, written.damping);
  for (TaylorMatrix ReducedBody::*field : {&ReducedBody::mdCM, &ReducedBody::J, &ReducedBody::Ct,
                                           &ReducedBody::Cr, &ReducedBody::Me, &ReducedBody::Gr,
                                           &ReducedBody::Ge, &ReducedBody::Oe, &ReducedBody::Ke,
                                           &ReducedBody::De, &ReducedBody::ksigma}) {
    EXPECT_TRUE(read.*field == written.*field);
  }
  EXPECT_TRUE(read.stiffening.K0t == written.stiffening.K0t);
  EXPECT_TRUE(read.stiffening.K0r == written.stiffening.K0r);
  EXPECT_TRUE(read.stiffening.K0omega == written.stiffening.K0omega);
  ExpectSame(read.node_positions, written.node_positions);
  EXPECT_EQ(read.node_sets, written.node_sets);
  ExpectSame(read.phi, written.phi);
  ASSERT_EQ(read.nodes.size(), 1u);
  const Node& node = read.nodes[0];
  EXPECT_EQ(node.name, "tip");
  EXPECT_EQ(node.coupling, "rigid");
  EXPECT_EQ(node.fe_nodes, written.nodes[0].fe_nodes);
  EXPECT_TRUE(node.origin == written.nodes[0].origin && node.phi == written.nodes[0].phi &&
              node.psi == written.nodes[0].psi && node.AP == written.nodes[0].AP);
  ASSERT_EQ(read.surfaces.size(), 1u);
  const ContactSurface& surface = read.surfaces[0];
  EXPECT_EQ(surface.name, "pad");
  EXPECT_EQ(surface.fe_nodes, written.surfaces[0].fe_nodes);
  EXPECT_EQ(surface.face_sizes, written.surfaces[0].face_sizes);
  EXPECT_EQ(surface.face_vertices, written.surfaces[0].face_vertices);
  ExpectSame(surface.vertices, written.surfaces[0].vertices);
  ExpectSame(surface.face_normals, written.surfaces[0].face_normals);
  ExpectSame(surface.phi, written.surfaces[0].phi);
  EXPECT_EQ(read.visual_surface.face_sizes, written.visual_surface.face_sizes);
  EXPECT_EQ(read.visual_surface.face_nodes, written.visual_surface.face_nodes);
  EXPECT_EQ(read.provenance.at("mesh"), "bracket.msh");
  EXPECT_TRUE(read.provenance.contains("tool_version"));
}

TEST(SidFile, BodyWithoutStiffeningNodesOrSurfacesRoundTrips) {
  const fs::path path = TempPath("plain.sid.h5");
  ReducedBody written = SampleBody();
  written.stiffening = {};
  written.nodes.clear();
  written.surfaces.clear();
  written.visual_surface = {};
  WriteReducedBody(path, written);
  EXPECT_FALSE(h5::File::Open(path).root().HasGroup("visual_surface"));
  const ReducedBody read = ReadReducedBody(path);
  EXPECT_TRUE(read.stiffening.empty());
  EXPECT_TRUE(read.nodes.empty());
  EXPECT_TRUE(read.surfaces.empty());
  EXPECT_TRUE(read.visual_surface.empty());
  EXPECT_TRUE(read.J == written.J);
}

// The file lists a group's members by name, so marker nodes and surfaces come back in name order
// whatever order the body held them in (a Craig-Bampton interface marker 'tip' before a `sid:`
// marker 'mid'): the digest holds (the reader said 'content digest mismatch' for such a body).
TEST(SidFile, NodesAndSurfacesOutOfNameOrderRoundTrip) {
  const fs::path path = TempPath("unordered.sid.h5");
  ReducedBody written = SampleBody();
  written.nodes.push_back(testing::RandomNode("mid", {1, 2}, "averaging", kModes));
  ContactSurface bottom = written.surfaces[0];
  bottom.name = "bottom";
  written.surfaces.push_back(bottom);
  WriteReducedBody(path, written);
  const ReducedBody read = ReadReducedBody(path);
  ASSERT_EQ(read.nodes.size(), 2u);
  EXPECT_EQ(read.nodes[0].name, "mid");
  EXPECT_EQ(read.nodes[1].name, "tip");
  EXPECT_TRUE(read.nodes[0].phi == written.nodes[1].phi);
  ASSERT_EQ(read.surfaces.size(), 2u);
  EXPECT_EQ(read.surfaces[0].name, "bottom");
  EXPECT_EQ(ContentDigest(read), ContentDigest(written));
}

// Every dataset under `group`, recursively: numeric ones must carry units, string ones cannot.
void ExpectUnitsEverywhere(const h5::Group& group, int* numeric_datasets) {
  for (const std::string& name : group.ChildNames()) {
    if (group.HasGroup(name)) {
      ExpectUnitsEverywhere(group.OpenGroup(name), numeric_datasets);
      continue;
    }
    bool is_string = true;
    try {
      group.ReadStrings(name);
    } catch (const InputError&) {
      is_string = false;
    }
    if (is_string) continue;
    ++*numeric_datasets;
    EXPECT_NO_THROW(group.ReadUnits(name)) << group.path() << "/" << name;
  }
}

TEST(SidFile, EveryNumericDatasetHasUnits) {
  const fs::path path = TempPath("units.sid.h5");
  WriteReducedBody(path, SampleBody());
  const h5::File file = h5::File::Open(path);
  int numeric_datasets = 0;
  ExpectUnitsEverywhere(file.root(), &numeric_datasets);
  EXPECT_GT(numeric_datasets, 50);
}

TEST(SidFile, InconsistentBodyIsAnInternalErrorNotAFile) {
  const fs::path path = TempPath("inconsistent.sid.h5");
  ReducedBody body = SampleBody();
  body.Gr.m1.pop_back();
  EXPECT_THROW(WriteReducedBody(path, body), InternalError);
  EXPECT_FALSE(fs::exists(path));
}

// The message of the InputError that reading `path` throws.
std::string ReadError(const fs::path& path) {
  return testing::InputErrorMessage([&] { ReadReducedBody(path); });
}

TEST(SidFile, ForeignHdf5FileIsRefusedByName) {
  const fs::path path = TempPath("foreign.h5");
  h5::File file = h5::File::Create(path);
  file.root().WriteScalar("x", 1.0, "1");
  file.Commit();
  EXPECT_EQ(ReadError(path), path.string() + ": not a flexmbs reduced body (no format 'flexmbs-sid')");
}

TEST(SidFile, WrongSchemaVersionIsRefusedByName) {
  const fs::path path = TempPath("old.sid.h5");
  h5::File file = h5::File::Create(path);
  file.root().SetStringAttribute("format", "flexmbs-sid");
  file.root().SetIntegerAttribute("schema_version", 1);
  file.Commit();
  EXPECT_EQ(ReadError(path), fmt::format("{0}: schema_version 1 was written by an earlier flexmbs, without "
                                         "checksums or content digest; regenerate it with `flexmbs reduce BODY.yaml "
                                         "-o {0}`",
                                         path.string()));
}

TEST(SidFile, NewerSchemaVersionIsRefusedByName) {
  const fs::path path = TempPath("newer.sid.h5");
  h5::File file = h5::File::Create(path);
  file.root().SetStringAttribute("format", "flexmbs-sid");
  file.root().SetIntegerAttribute("schema_version", kSidSchemaVersion + 1);
  file.Commit();
  EXPECT_NE(ReadError(path).find(fmt::format("schema_version {} is not supported", kSidSchemaVersion + 1)),
            std::string::npos);
}

// Runs `script` with Debian's python3 and its h5py, an HDF5 writer independent of ours.
void RunPython(const std::string& script) {
  FLEXMBS_CHECK(std::system(fmt::format("/usr/bin/python3 -c \"{}\"", script).c_str()) == 0,
                "h5py could not alter the test file");
}

// A file of schema 3 (variable-length strings, no checksums, no digest), as h5py writes its
// strings, is refused with the command that regenerates it, before any string is read.
TEST(SidFile, EarlierSchemaIsRefusedWithTheCommandThatRegeneratesIt) {
  const fs::path path = TempPath("schema3.sid.h5");
  RunPython(fmt::format("import h5py; f = h5py.File('{}', 'w'); f.attrs['format'] = 'flexmbs-sid'; "
                        "f.attrs['schema_version'] = 3; f.attrs['name'] = 'rod'; f.close()",
                        path.string()));
  EXPECT_EQ(ReadError(path), fmt::format("{0}: schema_version 3 was written by an earlier flexmbs, without "
                                         "checksums or content digest; regenerate it with `flexmbs reduce BODY.yaml "
                                         "-o {0}`",
                                         path.string()));
}

/// Multiplies /invariants/Ke's m0(0, 0) by 1.001 with h5py, rewriting the dataset with a valid
/// checksum and its units.
void EditKeInPlace(const fs::path& path) {
  RunPython(fmt::format("import h5py, numpy; g = h5py.File('{}', 'r+')['/invariants/Ke']; m = g['m0'][()]; "
                        "m[0, 0] *= 1.001; del g['m0']; g.create_dataset('m0', data=m, fletcher32=True)"
                        ".attrs['units'] = numpy.bytes_('N m/q^2')",
                        path.string()));
}

// A value changed by hand (h5py, the dataset rewritten with its units, so every checksum
// holds) is named as an edit by the content digest, in a file of either schema: 5 (XXH3-128)
// and the previous 4 (SHA-256), whose files stay readable.
TEST(SidFile, HandEditedValueIsNamedByTheContentDigest) {
  for (const int schema : {kSidOldestReadableSchemaVersion, kSidSchemaVersion}) {
    const fs::path path = TempPath(fmt::format("edited_{}.sid.h5", schema));
    WriteReducedBody(path, SampleBody(), schema);
    ASSERT_EQ(ReadSidSchemaVersion(path), schema);
    EditKeInPlace(path);
    EXPECT_NE(ReadError(path).find(path.string() + ": content digest mismatch: the body was damaged or edited "
                                                   "after `flexmbs reduce` wrote it (stored "),
              std::string::npos)
        << schema << ": " << ReadError(path);
  }
}

// The two lines tests/sid/content_digest.py prints for `path`: the digest it computes from the
// file with h5py and hashlib or python3-xxhash, as docs/sid.md describes it, and the stored one.
std::pair<std::string, std::string> PythonDigests(const fs::path& path) {
  FILE* pipe = popen(
      fmt::format("/usr/bin/python3 '{}/tests/sid/content_digest.py' '{}'", FLEXMBS_SOURCE_DIR, path.string()).c_str(),
      "r");
  EXPECT_NE(pipe, nullptr);
  if (pipe == nullptr) return {};
  char computed[128] = {}, stored[128] = {};
  const bool read = std::fscanf(pipe, "%127s %127s", computed, stored) == 2;
  EXPECT_EQ(pclose(pipe), 0);
  EXPECT_TRUE(read);
  return {computed, stored};
}

// A body written in each readable schema: the stored digest is the one an independent program
// computes from the file by the documented rule with the schema's hash (SHA-256 for 4, XXH3-128
// for 5), the reader checks it and returns the body, and `info --verify`'s reading holds.
TEST(SidFile, EachSchemasDigestIsItsHashOfTheDocumentedBytesAndReads) {
  const ReducedBody written = SampleBody();
  for (const auto& [schema, algorithm, hex_digits] :
       {std::tuple{kSidOldestReadableSchemaVersion, DigestAlgorithm::kSha256, 64},
        std::tuple{kSidSchemaVersion, DigestAlgorithm::kXxh3_128, 32}}) {
    const fs::path path = TempPath(fmt::format("schema_{}.sid.h5", schema));
    WriteReducedBody(path, written, schema);
    const auto [computed, stored] = PythonDigests(path);
    EXPECT_EQ(stored.size(), static_cast<std::size_t>(hex_digits)) << schema;
    EXPECT_EQ(computed, stored) << schema;
    EXPECT_EQ(stored, ContentDigest(written, algorithm)) << schema;
    EXPECT_EQ(ContentDigest(ReadReducedBody(path), algorithm), stored) << schema;
    EXPECT_GT(VerifyReducedBodyFile(path).datasets, 0) << schema;
  }
  EXPECT_NE(ContentDigest(written, DigestAlgorithm::kSha256), ContentDigest(written, DigestAlgorithm::kXxh3_128));
}

// A schema-5 body with one bit of the modes flipped on disk is refused with one line naming it.
TEST(SidFile, ADamagedBodyOfTheNewSchemaIsRefused) {
  const fs::path path = TempPath("flipped.sid.h5");
  WriteReducedBody(path, SampleBody());
  RunPython(fmt::format("import h5py; f = h5py.File('{0}', 'r'); d = f['/modes/phi']; "
                        "offset = d.id.get_chunk_info(0).byte_offset; f.close(); "
                        "g = open('{0}', 'r+b'); g.seek(offset + 3); b = g.read(1); g.seek(offset + 3); "
                        "g.write(bytes([b[0] ^ 0x10])); g.close()",
                        path.string()));
  const std::string error = ReadError(path);
  EXPECT_EQ(error.rfind(path.string() + ": /modes/phi: ", 0), 0u) << error;
  EXPECT_NE(error.find("Fletcher32"), std::string::npos) << error;
}

TEST(SidFile, TheDigestCoversEveryValueTheReaderReturns) {
  const fs::path path = TempPath("digest.sid.h5");
  const ReducedBody written = SampleBody();
  WriteReducedBody(path, written);
  EXPECT_EQ(ContentDigest(ReadReducedBody(path)), ContentDigest(written));
  ReducedBody changed = written;
  changed.phi(2, 1) = std::nextafter(changed.phi(2, 1), 2.0);
  EXPECT_NE(ContentDigest(changed), ContentDigest(written));
  changed = written;
  changed.nodes[0].coupling = "averaging";
  EXPECT_NE(ContentDigest(changed), ContentDigest(written));
  changed = written;
  changed.visual_surface.face_nodes[0] = 4;
  EXPECT_NE(ContentDigest(changed), ContentDigest(written));
}

TEST(SidFile, VisualSurfaceNodeOutOfRangeIsRefusedByName) {
  const fs::path path = TempPath("visual_range.sid.h5");
  WriteReducedBody(path, SampleBody());
  RunPython(fmt::format("import h5py, numpy; g = h5py.File('{}', 'r+')['visual_surface']; del g['face_nodes']; "
                        "g.create_dataset('face_nodes', data=numpy.array([0, 1, 2, 1, 2, 3, {}])).attrs['units'] = numpy.bytes_('1')",
                        path.string(), kNodes));
  EXPECT_EQ(ReadError(path), fmt::format("{}: inconsistent body: visual surface: FE node {} out of range",
                                         path.string(), kNodes));
}

TEST(SidFile, VisualSurfaceOfWrongSizeIsAnInternalError) {
  ReducedBody body = SampleBody();
  body.visual_surface.face_nodes.pop_back();
  EXPECT_THROW(WriteReducedBody(TempPath("visual_size.sid.h5"), body), InternalError);
}

TEST(SidFile, TruncatedFileIsOneLineError) {
  const fs::path path = TempPath("truncated.sid.h5");
  WriteReducedBody(path, SampleBody());
  fs::resize_file(path, fs::file_size(path) / 2);
  const std::string error = ReadError(path);
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

// The sample file with the dataset /invariants/Ct/<dataset> replaced by zeros of rows x 3 with
// `units`, altered by h5py.
fs::path WithAlteredCt(const std::string& file_name, const std::string& dataset, Eigen::Index rows,
                       const std::string& units) {
  const fs::path path = TempPath(file_name);
  WriteReducedBody(path, SampleBody());
  RunPython(fmt::format(
      "import h5py, numpy; f = h5py.File('{0}', 'r+'); g = f['/invariants/Ct']; del g['{1}']; "
      "g.create_dataset('{1}', data=numpy.zeros(({2}, 3))).attrs['units'] = numpy.bytes_('{3}'); f.close()",
      path.string(), dataset, rows, units));
  return path;
}

TEST(SidFile, WrongUnitsAreRefusedByName) {
  const fs::path path = WithAlteredCt("units_mm.sid.h5", "m0", kModes, "g mm/q");
  const std::string error = ReadError(path);
  EXPECT_NE(error.find("/invariants/Ct/m0"), std::string::npos) << error;
  EXPECT_NE(error.find("g mm/q"), std::string::npos) << error;
}

TEST(SidFile, MisShapedTaylorBlockIsRefusedByName) {
  const fs::path path = WithAlteredCt("shape.sid.h5", "m1", kModes * kModes - 1, "kg m/q^2");
  const std::string error = ReadError(path);
  EXPECT_EQ(error, fmt::format("{}: /invariants/Ct/m1: {} x 3, expected {} blocks of {} x 3", path.string(),
                               kModes * kModes - 1, kModes, kModes));
}

}  // namespace
}  // namespace flexmbs::sid
