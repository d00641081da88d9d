// End-to-end tests of `flexmbs info` and `flexmbs export` (docs/cli.md): a cube is reduced with
// `flexmbs reduce`, and the documented JSON summary must hold the numbers the file holds (read
// with sid::ReadReducedBody) and the analytic ones (mass, surface area); the ASCII SID export
// must hold the file's blocks; bad files are one-line input errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/h5_file.h"
#include "sid/sid_file.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::ExpectInputError;
using flexmbs::testing::Lines;
using flexmbs::testing::Outcome;
using flexmbs::testing::ReadFile;

constexpr int kExitOk = 0;  // docs/cli.md
const fs::path kData = fs::path(FLEXMBS_SOURCE_DIR) / "tests" / "data";

constexpr double kSteelDensity = 7850.0;  // kg/m^3
constexpr double kCubeEdge = 0.1;         // m, tests/data/cube.geo
// The tet mesh of a box fills it exactly: mass, face areas and plane coordinates agree to
// round-off.
constexpr double kRoundOff = 1e-9;

std::string Trim(const std::string& s) {
  const auto begin = s.find_first_not_of(' ');
  return begin == std::string::npos ? "" : s.substr(begin, s.find_last_not_of(' ') - begin + 1);
}

// The cube, reduced once per test process (free-free, 4 normal modes) with a marker on its top
// face, its bottom face as a contact surface and modal damping.
class InfoTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("flexmbs_info_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "out");
    std::ofstream(dir_ / "cube.yaml") << "name: cube\n"
                                      << "geometry: {file: " << (kData / "cube.geo").string()
                                      << ", mesh_size: 0.05, element_order: 1}\n"
                                      << "materials: {steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, "
                                         "density: 7850}}\n"
                                      << "material: steel\n"
                                      << "node_sets: [bottom, top]\n"
                                      << "reduction: {method: free_free, modes: 4}\n"
                                      << "sid:\n"
                                      << "  markers: [{name: lid, node_set: top, coupling: averaging}]\n"
                                      << "  contact_surfaces: [bottom]\n"
                                      << "  damping: {modal_ratio: 0.02}\n";
    body_file_ = dir_ / "cube.sid.h5";
    reduce_ = Run({"reduce", (dir_ / "cube.yaml").string(), "-o", body_file_.string()});
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    ASSERT_EQ(reduce_.exit_code, kExitOk) << reduce_.err;
  }

  static Outcome Run(const std::vector<std::string>& args) { return flexmbs::testing::RunFlexmbs(args, dir_); }

  // Files in out/ (where the tests export), temporaries included.
  static std::vector<std::string> OutputFiles() {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_ / "out")) names.push_back(entry.path().filename().string());
    return names;
  }

  static inline fs::path dir_;
  static inline fs::path body_file_;
  static inline Outcome reduce_;
};

// NaN in the file is null in JSON.
void ExpectSameNumbers(const nlohmann::json& j, const Eigen::VectorXd& v) {
  ASSERT_EQ(j.size(), static_cast<std::size_t>(v.size()));
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (std::isnan(v(k))) {
      EXPECT_TRUE(j[static_cast<std::size_t>(k)].is_null()) << k;
    } else {
      EXPECT_EQ(j[static_cast<std::size_t>(k)].get<double>(), v(k)) << k;
    }
  }
}

TEST_F(InfoTest, JsonHasTheDocumentedKeysAndTheFilesNumbers) {
  const Outcome run = Run({"info", body_file_.string(), "--json"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "");
  const nlohmann::json j = nlohmann::json::parse(run.out);
  const std::set<std::string> documented = {
      "file",       "format",     "schema_version", "name",       "mass_kg",    "center_of_mass_m",
      "inertia_about_com_kg_m2",  "fe_nodes",       "modes",      "mode_names", "mode_kinds",
      "frequency_hz", "damping",  "nodes",          "surfaces",   "visual_surface_faces",
      "stiffening", "provenance"};
  std::set<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.insert(key);
  EXPECT_EQ(keys, documented);

  const flexmbs::sid::ReducedBody body = flexmbs::sid::ReadReducedBody(body_file_);
  EXPECT_EQ(j["file"], body_file_.string());
  EXPECT_EQ(j["format"], "flexmbs-sid");
  EXPECT_EQ(j["schema_version"], flexmbs::sid::kSidSchemaVersion);
  EXPECT_EQ(j["name"], "cube");
  EXPECT_EQ(j["mass_kg"].get<double>(), body.mass);
  const double mass = kSteelDensity * std::pow(kCubeEdge, 3);
  EXPECT_NEAR(j["mass_kg"].get<double>(), mass, kRoundOff * mass);
  ExpectSameNumbers(j["center_of_mass_m"], body.center_of_mass);
  for (int i = 0; i < 3; ++i) ExpectSameNumbers(j["inertia_about_com_kg_m2"][i], body.inertia_about_center_of_mass.row(i).transpose());
  EXPECT_EQ(j["fe_nodes"].get<long>(), body.node_positions.cols());

  EXPECT_EQ(j["modes"], (nlohmann::json{{"rigid", 6}, {"normal", 4}, {"constraint", 0}, {"static_correction", 0},
                                        {"total", 10}}));
  EXPECT_EQ(j["mode_names"].get<std::vector<std::string>>(), body.mode_names);
  EXPECT_EQ(j["mode_kinds"].get<std::vector<std::string>>(), body.mode_kinds);
  ExpectSameNumbers(j["frequency_hz"], body.frequency_hz);
  EXPECT_EQ(j["damping"], body.damping);
  EXPECT_NE(body.damping, "none");

  ASSERT_EQ(j["nodes"].size(), 1u);
  ASSERT_EQ(body.nodes.size(), 1u);
  const nlohmann::json& lid = j["nodes"][0];
  EXPECT_EQ(lid["name"], "lid");
  EXPECT_EQ(lid["coupling"], "averaging");
  EXPECT_EQ(lid["fe_nodes"].get<std::size_t>(), body.node_sets.at("top").size());
  ExpectSameNumbers(lid["position_m"], body.nodes[0].origin.m0.col(0));
  EXPECT_NEAR(lid["position_m"][2].get<double>(), kCubeEdge, kRoundOff);  // on the top face z = a

  ASSERT_EQ(j["surfaces"].size(), 1u);
  const nlohmann::json& bottom = j["surfaces"][0];
  EXPECT_EQ(bottom["name"], "bottom");
  EXPECT_EQ(bottom["vertices"].get<long>(), body.surfaces[0].vertices.rows());
  EXPECT_EQ(bottom["faces"].get<std::size_t>(), body.surfaces[0].face_sizes.size());
  EXPECT_NEAR(bottom["area_m2"].get<double>(), kCubeEdge * kCubeEdge, kRoundOff * kCubeEdge * kCubeEdge);

  EXPECT_EQ(j["visual_surface_faces"].get<std::size_t>(), body.visual_surface.face_sizes.size());
  EXPECT_GT(body.visual_surface.face_sizes.size(), 0u) << "reduce always writes the visual surface";

  EXPECT_EQ(j["stiffening"].get<bool>(), !body.stiffening.empty());
  EXPECT_TRUE(j["stiffening"].get<bool>()) << "geometric stiffening is on by default";
  using Provenance = std::map<std::string, std::string>;
  EXPECT_EQ(j["provenance"].get<Provenance>(), body.provenance);
}

TEST_F(InfoTest, TextSummaryGoesToStdout) {
  const Outcome run = Run({"info", body_file_.string()});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "");
  for (const std::string line : {"body            cube\n", "mass            7.85 kg\n",
                                 "modes           6 rigid, 4 normal, 0 constraint, 0 static_correction (10 in all)\n",
                                 "surfaces        1\n", "stiffening      yes\n"}) {
    EXPECT_NE(run.out.find(line), std::string::npos) << line << "\n" << run.out;
  }
}

// A top-level Taylor block of an ASCII SID file as a dense m0 (docs/sid-ascii.md).
Eigen::MatrixXd AsciiBlockM0(const std::vector<std::string>& lines, const std::string& name) {
  std::size_t at = 0;
  while (at < lines.size() && Trim(lines[at]) != name) ++at;
  EXPECT_LT(at, lines.size()) << "no block " << name;
  Eigen::MatrixXd m0;
  for (++at; at < lines.size() && Trim(lines[at]) != "end " + name; ++at) {
    const std::string line = Trim(lines[at]);
    const std::string key = Trim(line.substr(0, line.find('='))), value = Trim(line.substr(line.find('=') + 1));
    if (key == "nrow") m0.resize(std::stol(value), m0.cols());
    if (key == "ncol") m0 = Eigen::MatrixXd::Zero(m0.rows(), std::stol(value));
    if (key.starts_with("m0(")) {
      int i = 0, k = 0;
      EXPECT_EQ(std::sscanf(key.c_str(), "m0(%d,%d)", &i, &k), 2) << key;
      std::string number = value;
      std::replace(number.begin(), number.end(), 'D', 'E');
      m0(i - 1, k - 1) = std::stod(number);
    }
  }
  return m0;
}

TEST_F(InfoTest, ExportWritesTheBodysSidBlocks) {
  const fs::path output = dir_ / "out" / "cube.SID_FEM";
  const Outcome run = Run({"export", body_file_.string(), "-o", output.string(), "--format", "sid-ascii"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_NE(run.out.find("wrote           " + output.string()), std::string::npos) << run.out;
  EXPECT_EQ(OutputFiles(), std::vector<std::string>{"cube.SID_FEM"});

  const flexmbs::sid::ReducedBody body = flexmbs::sid::ReadReducedBody(body_file_);
  const std::vector<std::string> lines = Lines(ReadFile(output));
  ASSERT_GT(lines.size(), 3u);
  std::istringstream header(lines[0]);
  int nodes = 0, modes = 0;
  header >> nodes >> modes;
  EXPECT_EQ(nodes, 1);
  EXPECT_EQ(modes, 10);
  EXPECT_EQ(Trim(lines[1]), "part");
  EXPECT_EQ(Trim(lines.back()), "end part");
  // Order-0 blocks as they are, J as [xx, yy, zz, xy, xz, yz], each value exactly.
  EXPECT_TRUE(AsciiBlockM0(lines, "Ke") == body.Ke.m0);
  EXPECT_TRUE(AsciiBlockM0(lines, "Me") == body.Me.m0);
  const Eigen::Matrix3d& J = body.J.m0;
  Eigen::MatrixXd J6(6, 1);
  J6 << J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2);
  EXPECT_TRUE(AsciiBlockM0(lines, "J") == J6);
  fs::remove(output);
}

// --- bad input: one line, exit 2 --------------------------------------------------------------

TEST_F(InfoTest, MissingFileIsAnInputError) {
  ExpectInputError(Run({"info", (dir_ / "absent.sid.h5").string()}), (dir_ / "absent.sid.h5").string() + ": no such file");
}

TEST_F(InfoTest, FileThatIsNotHdf5IsAnInputError) {
  ExpectInputError(Run({"info", (kData / "cube.yaml").string()}), "cube.yaml: not an HDF5 file");
}

TEST_F(InfoTest, Hdf5FileOfAnotherKindIsAnInputError) {
  const fs::path foreign = dir_ / "foreign.h5", unmarked = dir_ / "unmarked.h5";
  {
    flexmbs::h5::File file = flexmbs::h5::File::Create(foreign);
    file.root().SetStringAttribute("format", "someone-else");
    file.Commit();
    flexmbs::h5::File plain = flexmbs::h5::File::Create(unmarked);
    plain.Commit();
  }
  ExpectInputError(Run({"info", foreign.string()}),
                   foreign.string() + ": not a file flexmbs info reads (format 'someone-else'; it reads: flexmbs-sid; with --verify also flexmbs-results)");
  ExpectInputError(Run({"info", unmarked.string()}),
                   unmarked.string() + ": not a file flexmbs info reads (no 'format' attribute; it reads: flexmbs-sid; with --verify also flexmbs-results)");
}

// docs/cli.md: without --verify, info summarises bodies only; a results file is named as such
// (its summary: scripts/plot_results.py).
TEST_F(InfoTest, ResultsFileWithoutVerifyIsAnInputError) {
  const fs::path results = dir_ / "results.h5";
  {
    flexmbs::h5::File file = flexmbs::h5::File::Create(results);
    file.root().SetStringAttribute("format", "flexmbs-results");
    file.Commit();
  }
  ExpectInputError(Run({"info", results.string()}),
                   results.string() + ": not a file flexmbs info reads (format 'flexmbs-results'; it reads: flexmbs-sid; with --verify also flexmbs-results)");
}

TEST_F(InfoTest, TruncatedBodyIsAnInputErrorForInfoAndExport) {
  const fs::path truncated = dir_ / "truncated.sid.h5";
  fs::copy_file(body_file_, truncated, fs::copy_options::overwrite_existing);
  fs::resize_file(truncated, fs::file_size(body_file_) / 2);
  ExpectInputError(Run({"info", truncated.string()}), truncated.string() + ": ");
  ExpectInputError(Run({"export", truncated.string(), "-o", (dir_ / "out" / "t.SID_FEM").string(), "--format",
                        "sid-ascii"}),
                   truncated.string() + ": ");
  EXPECT_TRUE(OutputFiles().empty());
}

// `info --verify`: the reduced cube is intact (exit 0, one line); the same file with one byte of
// its mode shapes flipped is refused by the checksum of the chunk holding it (exit 2, one line).
TEST_F(InfoTest, VerifySaysIntactOrNamesTheDamage) {
  const Outcome intact = Run({"info", "--verify", body_file_.string()});
  EXPECT_EQ(intact.exit_code, kExitOk) << intact.err;
  ASSERT_EQ(Lines(intact.out).size(), 1u) << intact.out;
  EXPECT_TRUE(intact.out.starts_with(body_file_.string() + ": intact (flexmbs-sid; ")) << intact.out;
  EXPECT_NE(intact.out.find("every checksum holds; content digest holds"), std::string::npos) << intact.out;

  const fs::path damaged = dir_ / "damaged.sid.h5";
  fs::copy_file(body_file_, damaged, fs::copy_options::overwrite_existing);
  std::string bytes = ReadFile(damaged);
  const std::size_t middle = bytes.size() / 2;  // inside /modes/phi, the largest dataset
  bytes[middle] = static_cast<char>(bytes[middle] ^ 0x10);
  std::ofstream(damaged, std::ios::binary | std::ios::trunc) << bytes;
  ExpectInputError(Run({"info", "--verify", damaged.string()}), damaged.string() + ": ");
}

TEST_F(InfoTest, ExportOfAnUnknownFormatIsAnInputError) {
  ExpectInputError(Run({"export", body_file_.string(), "-o", (dir_ / "out" / "c.txt").string(), "--format", "adams"}),
                   "--format adams: unknown format (known: sid-h5, sid-ascii)");
  ExpectInputError(Run({"export", body_file_.string(), "-o", (dir_ / "out" / "c.txt").string()}),
                   "--format is required");
  EXPECT_TRUE(OutputFiles().empty());
}

TEST_F(InfoTest, ExportIntoAMissingFolderFailsBeforeReading) {
  const fs::path output = dir_ / "no_such_folder" / "c.SID_FEM";
  ExpectInputError(Run({"export", (dir_ / "absent.sid.h5").string(), "-o", output.string(), "--format", "sid-ascii"}),
                   "-o " + output.string() + ": folder '" + (dir_ / "no_such_folder").string() + "' does not exist");
}

}  // namespace
