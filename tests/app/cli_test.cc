// End-to-end tests of the `flexmbs` binary: exit codes, one-line errors, help, and the
// documented JSON report of `flexmbs mesh` (docs/cli.md).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sid/sid_file.h"
#include "tests/app/block_body.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;

// Exit code of success (docs/cli.md); kExitInputError and the runner: flexmbs_process.h.
constexpr int kExitOk = 0;
using flexmbs::testing::ExpectInputError;
using flexmbs::testing::kExitInputError;
using flexmbs::testing::kFlexmbsBinary;
using flexmbs::testing::Lines;
using flexmbs::testing::Outcome;
using flexmbs::testing::ReadFile;
using flexmbs::testing::ShellQuote;

const fs::path kData = fs::path(FLEXMBS_SOURCE_DIR) / "tests" / "data";

constexpr double kSteelDensity = 7850.0;  // kg/m^3
constexpr double kCubeEdge = 0.1;         // m, tests/data/cube.geo
// The tet mesh of a box fills it exactly: mass and centre agree to round-off.
constexpr double kRoundOff = 1e-9;

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kFlexmbsBinary)) << kFlexmbsBinary << " is not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("flexmbs_cli_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Runs `flexmbs args...` in this test's folder.
  Outcome Flexmbs(const std::vector<std::string>& args) const { return flexmbs::testing::RunFlexmbs(args, dir_); }

  // A valid body: the cube of tests/data as a coarse tet4 mesh. Cases edit its text.
  std::string CubeBody() const {
    return "name: cube\n"
           "geometry:\n"
           "  file: " +
           (kData / "cube.geo").string() +
           "\n"
           "  mesh_size: 0.05\n"
           "  element_order: 1\n"
           "materials:\n"
           "  steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}\n"
           "material: steel\n"
           "node_sets: [bottom, top]\n";
  }

  fs::path WriteBody(const std::string& text) const {
    std::ofstream(dir_ / "body.yaml") << text;
    return dir_ / "body.yaml";
  }

  // Files left in out/ (where --matrix-market writes), temporaries included.
  std::vector<std::string> OutputFiles() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_ / "out")) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

  fs::path dir_;
};

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' is not in the body text";
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}


// --- help and the command line ---

TEST_F(CliTest, HelpWorksForTheProgramAndEverySubcommand) {
  const Outcome top = Flexmbs({"--help"});
  EXPECT_EQ(top.exit_code, kExitOk);
  EXPECT_EQ(top.err, "");
  // The subcommands are the names listed under "Subcommands:" in the top-level help.
  std::vector<std::string> subcommands;
  bool listing = false;
  for (const std::string& line : Lines(top.out)) {
    if (line.starts_with("Subcommands:")) {
      listing = true;
    } else if (listing && line.starts_with("  ")) {
      std::istringstream words(line);
      std::string name;
      words >> name;
      subcommands.push_back(name);
    } else if (listing && !line.empty()) {
      listing = false;
    }
  }
  ASSERT_FALSE(subcommands.empty()) << top.out;
  EXPECT_NE(std::find(subcommands.begin(), subcommands.end(), "mesh"), subcommands.end());
  for (const std::string& name : subcommands) {
    const Outcome help = Flexmbs({name, "--help"});
    EXPECT_EQ(help.exit_code, kExitOk) << name;
    EXPECT_EQ(help.err, "") << name;
    EXPECT_NE(help.out.find("Usage: flexmbs " + name), std::string::npos) << help.out;
  }
}

TEST_F(CliTest, VersionIsOneLine) {
  const Outcome run = Flexmbs({"--version"});
  EXPECT_EQ(run.exit_code, kExitOk);
  EXPECT_EQ(Lines(run.out).size(), 1u) << run.out;
}

TEST_F(CliTest, CommandLineErrorsAreOneLineInputErrors) {
  ExpectInputError(Flexmbs({}), "A subcommand is required");
  ExpectInputError(Flexmbs({"mesh"}), "body is required");
  ExpectInputError(Flexmbs({"mesh", (kData / "cube.yaml").string(), "--bogus"}), "--bogus");
}

// --- a valid body ---

TEST_F(CliTest, MeshJsonHasTheDocumentedKeysAndValues) {
  const Outcome run = Flexmbs({"mesh", (kData / "cube.yaml").string(), "--json"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "") << "progress goes to a terminal only";
  const nlohmann::json j = nlohmann::json::parse(run.out);  // throws if not JSON

  const std::set<std::string> documented = {"body",
                                            "geometry_file",
                                            "nodes",
                                            "elements",
                                            "dofs",
                                            "mass_matrix",
                                            "mass_kg",
                                            "center_of_mass_m",
                                            "inertia_about_com_kg_m2",
                                            "stiffness_nonzeros",
                                            "mass_nonzeros",
                                            "node_sets",
                                            "seconds"};
  std::set<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.insert(key);
  EXPECT_EQ(keys, documented);

  EXPECT_EQ(j["body"], "cube");
  EXPECT_EQ(j["geometry_file"], (kData / "cube.geo").string());
  EXPECT_EQ(j["dofs"].get<long>(), 3 * j["nodes"].get<long>());
  ASSERT_TRUE(j["elements"].is_object());
  EXPECT_GT(j["elements"]["tet4"].get<long>(), 0);
  EXPECT_EQ(j["mass_matrix"], "consistent");
  const double mass = kSteelDensity * std::pow(kCubeEdge, 3);
  EXPECT_NEAR(j["mass_kg"].get<double>(), mass, kRoundOff * mass);
  ASSERT_EQ(j["center_of_mass_m"].size(), 3u);
  for (const auto& x : j["center_of_mass_m"])
    EXPECT_NEAR(x.get<double>(), kCubeEdge / 2, kRoundOff);
  ASSERT_EQ(j["inertia_about_com_kg_m2"].size(), 3u);
  const double I = mass * kCubeEdge * kCubeEdge / 6.0;  // cube about its centre: m a^2 / 6
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(j["inertia_about_com_kg_m2"][i].size(), 3u);
    EXPECT_NEAR(j["inertia_about_com_kg_m2"][i][i].get<double>(), I, kRoundOff * I);
  }
  EXPECT_GT(j["stiffness_nonzeros"].get<long>(), 0);
  EXPECT_GT(j["mass_nonzeros"].get<long>(), 0);
  EXPECT_GT(j["node_sets"]["bottom"].get<long>(), 0);
  EXPECT_GT(j["node_sets"]["top"].get<long>(), 0);
  EXPECT_GE(j["seconds"]["mesh"].get<double>(), 0.0);
  EXPECT_GE(j["seconds"]["assembly"].get<double>(), 0.0);
}

TEST_F(CliTest, MeshTextReportGoesToStdout) {
  const Outcome run = Flexmbs({"mesh", (kData / "cube.yaml").string()});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_NE(run.out.find("body            cube\n"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("mass            7.85 kg\n"), std::string::npos) << run.out;
}

TEST_F(CliTest, MatrixMarketWritesKAndM) {
  const std::string prefix = (dir_ / "out" / "cube").string();
  const Outcome run =
      Flexmbs({"mesh", (kData / "cube.yaml").string(), "--json", "--matrix-market", prefix});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  const long dofs = nlohmann::json::parse(run.out)["dofs"].get<long>();
  std::vector<std::string> files = OutputFiles();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"cube_K.mtx", "cube_M.mtx"}));
  for (const std::string name : {"cube_K.mtx", "cube_M.mtx"}) {
    std::ifstream in(dir_ / "out" / name);
    std::string header;
    long rows = 0, cols = 0, entries = 0;
    std::getline(in, header);
    in >> rows >> cols >> entries;
    EXPECT_EQ(header, "%%MatrixMarket matrix coordinate real symmetric") << name;
    EXPECT_EQ(rows, dofs) << name;
    EXPECT_EQ(cols, dofs) << name;
    EXPECT_GT(entries, 0) << name;
  }
}

TEST_F(CliTest, MatrixMarketIntoMissingFolderFailsBeforeMeshing) {
  const std::string prefix = (dir_ / "no_such_folder" / "cube").string();
  ExpectInputError(Flexmbs({"mesh", (kData / "cube.yaml").string(), "--matrix-market", prefix}),
                   "--matrix-market " + prefix + ": folder '" + (dir_ / "no_such_folder").string() +
                       "' does not exist");
}

// --- reduce ---

// `seconds.eigensolver` of `reduce --json` (docs/cli.md): every field present, the parts within
// the eigen-solve's total, which lies within the reduction's, and at least one factorisation.
void ExpectEigensolverSplit(const nlohmann::json& seconds) {
  ASSERT_TRUE(seconds.contains("eigensolver")) << seconds.dump();
  const nlohmann::json& e = seconds["eigensolver"];
  for (const char* key : {"seconds", "factorization_seconds", "sturm_seconds", "krylov_seconds", "factorizations",
                          "operator_applications", "krylov_runs", "restarts", "missed_mode_check"}) {
    EXPECT_TRUE(e.contains(key)) << key;
  }
  const double total = e["seconds"].get<double>();
  const double factorization = e["factorization_seconds"].get<double>();
  const double sturm = e["sturm_seconds"].get<double>();
  const double krylov = e["krylov_seconds"].get<double>();
  EXPECT_GT(factorization, 0.0);
  EXPECT_GE(sturm, 0.0);
  EXPECT_GE(krylov, 0.0);
  EXPECT_LE(factorization + sturm + krylov, total);
  EXPECT_LE(total, seconds["reduction"].get<double>());
  EXPECT_GE(e["factorizations"].get<int>(), 1);
  EXPECT_GE(e["krylov_runs"].get<int>(), 1);
  EXPECT_GE(e["operator_applications"].get<int>(), e["krylov_runs"].get<int>());
  EXPECT_GE(e["restarts"].get<int>(), 0);
  // The cube is small: the automatic check is the Sturm count (spectra_eigensolver.cc).
  EXPECT_EQ(e["missed_mode_check"], "sturm_count");
  EXPECT_GT(sturm, 0.0);
}

TEST_F(CliTest, ReduceWritesTheBodyFileItReports) {
  const fs::path body = WriteBody(CubeBody() + "reduction: {method: free_free, modes: 4}\n");
  const fs::path output = dir_ / "out" / "cube.sid.h5";
  const Outcome run = Flexmbs({"reduce", body.string(), "-o", output.string(), "--json"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  EXPECT_EQ(run.err, "");
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["modes"]["rigid"], 6);
  EXPECT_EQ(j["modes"]["normal"], 4);
  EXPECT_EQ(j["modes"]["total"], 10);
  ExpectEigensolverSplit(j["seconds"]);
  // The free body's automatic shift: K (singular) is factorised first, then K - sigma M.
  EXPECT_GE(j["seconds"]["eigensolver"]["factorizations"].get<int>(), 2);
  const flexmbs::sid::ReducedBody file = flexmbs::sid::ReadReducedBody(output);
  ASSERT_EQ(file.phi.cols(), 10);
  EXPECT_EQ(file.mode_kinds[0], "rigid");
  EXPECT_EQ(file.mode_kinds[9], "normal");
  for (int k = 6; k < 10; ++k) {
    EXPECT_EQ(file.frequency_hz(k), j["frequency_hz"][static_cast<std::size_t>(k)].get<double>());
    EXPECT_GT(file.frequency_hz(k), 0.0);
  }
  // The basis is M-orthonormal: the reduced mass matrix is the identity.
  EXPECT_LT((file.Me.m0 - Eigen::MatrixXd::Identity(10, 10)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_EQ(OutputFiles(), std::vector<std::string>{"cube.sid.h5"});
}

TEST_F(CliTest, ReduceJsonReportsTheCraigBamptonEigenSolveWithOneFactorisationOfTheHeldBody) {
  const fs::path body = WriteBody(CubeBody() +
                                  "reduction:\n  method: craig_bampton\n  modes: 2\n  interfaces:\n"
                                  "    - {node_set: bottom, coupling: rigid}\n    - {node_set: top, coupling: rigid}\n");
  const Outcome run = Flexmbs({"reduce", body.string(), "-o", (dir_ / "out" / "cb.sid.h5").string(), "--json"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["modes"]["constraint"], 12);
  ExpectEigensolverSplit(j["seconds"]);
  // K_oo once (constraint modes and the shift-invert operator), plus the Sturm count's LDL^T.
  EXPECT_EQ(j["seconds"]["eigensolver"]["factorizations"], 2);
}

TEST_F(CliTest, ReduceWithoutAReductionSectionIsAnInputError) {
  ExpectInputError(Flexmbs({"reduce", (kData / "cube.yaml").string(), "-o", (dir_ / "out" / "c.sid.h5").string()}),
                   "cube.yaml:2:1: missing key 'reduction'");
}

TEST_F(CliTest, ReduceIntoMissingFolderFailsBeforeMeshing) {
  const fs::path output = dir_ / "no_such_folder" / "c.sid.h5";
  ExpectInputError(Flexmbs({"reduce", (kData / "cube.yaml").string(), "-o", output.string()}),
                   "-o " + output.string() + ": folder '" + (dir_ / "no_such_folder").string() + "' does not exist");
}

TEST_F(CliTest, FailedReductionLeavesNoFile) {
  const fs::path body = WriteBody(CubeBody() + "reduction: {method: free_free, modes: 100000}\n");
  const Outcome run = Flexmbs({"reduce", body.string(), "-o", (dir_ / "out" / "c.sid.h5").string()});
  EXPECT_EQ(run.exit_code, kExitInputError) << run.err;
  EXPECT_EQ(Lines(run.err).size(), 1u) << run.err;
  EXPECT_EQ(OutputFiles(), std::vector<std::string>{});
}

TEST_F(CliTest, ReduceUnderMpirunWithTwoRanksGivesTheSerialResult) {
  // Backend agreement bound of the issue; both solvers reach about 1e-11 alone here.
  constexpr double kAgreement = 1e-8;
  const std::string clamped = "{method: fixed_interface, supports: [root], modes: 6, eigensolver: ";
  std::ofstream(dir_ / "serial.yaml") << flexmbs::testing::BlockBody(dir_, clamped + "spectra}");
  std::ofstream(dir_ / "mpi.yaml") << flexmbs::testing::BlockBody(dir_, clamped + "slepc}");
  const fs::path serial = dir_ / "out" / "serial.sid.h5", mpi = dir_ / "out" / "mpi.sid.h5";
  ASSERT_EQ(Flexmbs({"reduce", (dir_ / "serial.yaml").string(), "-o", serial.string()}).exit_code, kExitOk);
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                              std::string(FLEXMBS_MPIEXEC) + " -n 2 " + kFlexmbsBinary.string() + " reduce " +
                              (dir_ / "mpi.yaml").string() + " -o " + mpi.string() + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const auto a = flexmbs::sid::ReadReducedBody(serial);
  const auto b = flexmbs::sid::ReadReducedBody(mpi);
  ASSERT_EQ(a.phi.cols(), b.phi.cols());
  for (Eigen::Index k = 0; k < a.phi.cols(); ++k) {
    EXPECT_NEAR(b.frequency_hz(k), a.frequency_hz(k), kAgreement * a.frequency_hz(k)) << "mode " << k;
    // Modal assurance criterion of the pair: 1 for the same shape (any sign or scale).
    const double mac = std::pow(a.phi.col(k).dot(b.phi.col(k)), 2) /
                       (a.phi.col(k).squaredNorm() * b.phi.col(k).squaredNorm());
    EXPECT_GT(mac, 1.0 - kAgreement) << "mode " << k;
  }
}

TEST_F(CliTest, CompareOfABodyWithItselfPairsEveryModeExactly) {
  const fs::path body = WriteBody(CubeBody() + "reduction: {method: free_free, modes: 3}\n");
  const fs::path file = dir_ / "out" / "cube.sid.h5";
  ASSERT_EQ(Flexmbs({"reduce", body.string(), "-o", file.string()}).exit_code, kExitOk);
  const Outcome run = Flexmbs({"compare", file.string(), file.string(), "--json"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j["pairs"].size(), 9u);
  for (const auto& pair : j["pairs"]) {
    EXPECT_EQ(pair["mode_a"], pair["mode_b"]);
    EXPECT_EQ(pair["relative_error"].get<double>(), 0.0);
    EXPECT_NEAR(pair["mac"].get<double>(), 1.0, 1e-12);
  }
  // A free-free basis carries the whole mass in its rigid translations.
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(j["effective_mass_fraction"]["a"][d].get<double>(), 1.0, 1e-10);
}

TEST_F(CliTest, CompareOfANonBodyFileIsAnInputError) {
  ExpectInputError(Flexmbs({"compare", (kData / "cube.yaml").string(), (kData / "cube.yaml").string()}),
                   "cube.yaml: not an HDF5 file");
}

// --- bad bodies: one line, exit 2, and no output files ---
//
// One case per code path that reports an input error. tests/fem/body_spec_test.cc and
// gmsh_import_test.cc check every message exactly, including the cases not repeated here
// (Poisson's ratio, density, unknown keys, wrong types, element order, ...).

class CliBadBodyTest : public CliTest {
 protected:
  // Runs `flexmbs mesh body --matrix-market out/m`, expects an input error naming
  // `expected`, and that nothing was written.
  void ExpectRejected(const fs::path& body, const std::string& expected) {
    const Outcome run =
        Flexmbs({"mesh", body.string(), "--matrix-market", (dir_ / "out" / "m").string()});
    ExpectInputError(run, expected);
    EXPECT_TRUE(OutputFiles().empty()) << "files left behind after: " << run.err;
  }
  void ExpectRejected(const std::string& body_text, const std::string& expected) {
    ExpectRejected(WriteBody(body_text), expected);
  }
};

TEST_F(CliBadBodyTest, MissingBodyFile) {
  ExpectRejected(dir_ / "absent.yaml", (dir_ / "absent.yaml").string() +
                                           ": cannot open the file: No such file or directory");
}

TEST_F(CliBadBodyTest, BodyFileThatIsADirectory) {
  ExpectRejected(dir_ / "out", (dir_ / "out").string() + ": is a directory, not a YAML file");
}

TEST_F(CliBadBodyTest, MissingGeometryFile) {
  ExpectRejected(Replace(CubeBody(), (kData / "cube.geo").string(), "nope.geo"),
                 "body.yaml:3:9: geometry.file: 'nope.geo' does not exist");
}

TEST_F(CliBadBodyTest, UnknownNodeSet) {
  ExpectRejected(
      Replace(CubeBody(), "[bottom, top]", "[bottom, tip]"),
      "body.yaml: " + (kData / "cube.geo").string() +
          ": node set 'tip': no physical group of that name (the file has: block, bottom, top)");
}

TEST_F(CliBadBodyTest, UnknownRegion) {
  ExpectRejected(Replace(CubeBody(), "material: steel", "regions: {beam: steel}"),
                 "body.yaml: regions: 'beam' is not a physical volume of " +
                     (kData / "cube.geo").string() + " (it has: block)");
}

TEST_F(CliBadBodyTest, InvertedElementIsNamedWithItsNodes) {
  const std::string body = Replace(
      Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "inverted_tet.msh").string()),
      "[bottom, top]", "[base]");
  ExpectRejected(body,
                 "body.yaml: " + (kData / "inverted_tet.msh").string() +
                     ": region 'solid': tet4 element 3 with nodes [1, 2, 3, 5] has non-positive "
                     "Jacobian determinant -1");
}

TEST_F(CliBadBodyTest, NonPositiveYoungsModulus) {
  ExpectRejected(Replace(CubeBody(), "2.1e11", "-2e11"),
                 "body.yaml: material 'steel': Young's modulus -2e+11 must be > 0");
}

TEST_F(CliBadBodyTest, EmptyMesh) {
  ExpectRejected(Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "empty.msh").string()),
                 "empty.msh: the mesh has no elements; flexmbs needs a solid (3-D) mesh");
}

TEST_F(CliBadBodyTest, SurfaceOnlyGeometry) {
  ExpectRejected(
      Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "square.geo").string()),
      "square.geo: the mesh is 2-D (");
}

TEST_F(CliBadBodyTest, UnsupportedPyramid) {
  ExpectRejected(
      Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "pyramid.msh").string()),
      "pyramid.msh: region 'solid': element 1 is a pyramid5 (gmsh type 7), which flexmbs "
      "does not support");
}

TEST_F(CliBadBodyTest, UnsupportedHex27) {
  ExpectRejected(Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "hex27.msh").string()),
                 "hex27.msh: region 'block': element 1 is a hex27 (gmsh type 12), which flexmbs "
                 "does not support");
}

TEST_F(CliBadBodyTest, MalformedYamlGivesLineAndColumn) {
  ExpectRejected(std::string("name: cube\n  geometry: x\n"),
                 "body.yaml:2:11: malformed YAML: illegal map value");
}

TEST_F(CliBadBodyTest, NonPositiveMeshSize) {
  ExpectRejected(Replace(CubeBody(), "mesh_size: 0.05", "mesh_size: -1"),
                 "body.yaml:4:14: geometry.mesh_size: mesh size -1 m must be > 0");
}

TEST_F(CliBadBodyTest, GeoSyntaxError) {
  ExpectRejected(
      Replace(CubeBody(), (kData / "cube.geo").string(), (kData / "syntax_error.geo").string()),
      "body.yaml: " + (kData / "syntax_error.geo").string() +
          ": gmsh could not read the file: line 3: syntax error (1)");
}

// OpenCASCADE prints STEP parse errors to stdout on its own; ExpectInputError checks stdout
// stays empty.
TEST_F(CliBadBodyTest, BadStepFilePrintsOnlyTheError) {
  std::ofstream(dir_ / "part.step") << "this is not STEP\n";
  ExpectRejected(Replace(CubeBody(), (kData / "cube.geo").string(), (dir_ / "part.step").string()),
                 "part.step: gmsh could not read the file: Could not read file");
}

}  // namespace
