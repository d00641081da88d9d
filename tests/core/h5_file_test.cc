#include "core/h5_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>

#include "core/error.h"

namespace flexmbs::h5 {
namespace {

namespace fs = std::filesystem;

// HDF5 stores IEEE-754 binary64 and two's-complement int64 verbatim, so every round trip here
// is exact: values are compared with == (a tolerance of zero), never approximately. The same
// holds against h5py, which computes its expected values with the same IEEE operations.

// Debian's Python packages (h5py) are seen only by this interpreter (STACK.md).
constexpr const char* kSystemPython = "/usr/bin/python3";

class H5FileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() /
           ("flexmbs_h5_test_" + std::to_string(::getpid()) + "_" + test);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  /// Names of the files in the test folder, sorted.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

/// The message of the InputError `action` throws ("" and a test failure if none).
template <typename Action>
std::string InputErrorOf(Action&& action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

bool IsOneLine(const std::string& message) {
  return !message.empty() && message.find('\n') == std::string::npos;
}

/// A 3x5 matrix (non-square, so a transposed layout would show) with values that need all
/// 64 bits, and the extremes of binary64 in its last row.
Eigen::MatrixXd NonSquareMatrix() {
  Eigen::MatrixXd m(3, 5);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 5; ++c) m(r, c) = r + c / 7.0;
  }
  m(1, 2) = std::numbers::pi;
  m(2, 0) = std::numeric_limits<double>::denorm_min();
  m(2, 1) = std::numeric_limits<double>::max();
  m(2, 2) = std::numeric_limits<double>::lowest();
  m(2, 3) = -0.0;
  m(2, 4) = std::numeric_limits<double>::infinity();
  return m;
}

void WriteFileWithMatrix(const fs::path& path) {
  File file = File::Create(path);
  file.root().CreateGroup("refmod").WriteMatrix("M", NonSquareMatrix(), "kg");
  file.Commit();
}

// ---------------------------------------------------------------------------------------------
// Round trips

TEST_F(H5FileTest, MatrixRoundTripsExactlyWithDimsRowsThenCols) {
  const fs::path path = dir_ / "body.sid.h5";
  const Eigen::MatrixXd written = NonSquareMatrix();
  WriteFileWithMatrix(path);

  const File file = File::Open(path);
  const Group refmod = file.root().OpenGroup("refmod");
  EXPECT_EQ(refmod.Shape("M"), (std::vector<std::int64_t>{3, 5}));
  const Eigen::MatrixXd read = refmod.ReadMatrix("M");
  ASSERT_EQ(read.rows(), 3);
  ASSERT_EQ(read.cols(), 5);
  EXPECT_TRUE(read == written) << read;
  EXPECT_TRUE(std::signbit(read(2, 3))) << "-0.0 keeps its sign";
}

TEST_F(H5FileTest, ExpressionsAreWrittenAsTheirValues) {
  const fs::path path = dir_ / "expr.h5";
  const Eigen::MatrixXd m = NonSquareMatrix();
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteMatrix("block", m.topRightCorner(2, 3), "m");
    root.WriteMatrix("transposed", m.transpose(), "m");
    root.WriteVector("row", m.row(1).transpose(), "m");  // strided in memory
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_TRUE(root.ReadMatrix("block") == m.topRightCorner(2, 3));
  EXPECT_EQ(root.Shape("transposed"), (std::vector<std::int64_t>{5, 3}));
  EXPECT_TRUE(root.ReadMatrix("transposed") == m.transpose());
  EXPECT_TRUE(root.ReadVector("row") == m.row(1).transpose());
}

TEST_F(H5FileTest, EmptyMatricesAndVectorsKeepTheirShape) {
  const fs::path path = dir_ / "empty.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteMatrix("no_modes", Eigen::MatrixXd(4, 0), "1");
    root.WriteMatrix("no_nodes", Eigen::MatrixXd(0, 3), "m");
    root.WriteVector("no_frequencies", Eigen::VectorXd(0), "Hz");
    root.WriteIntegers("no_ids", std::vector<int>{}, "1");
    root.WriteStrings("no_names", {});
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  const Eigen::MatrixXd no_modes = root.ReadMatrix("no_modes");
  EXPECT_EQ(no_modes.rows(), 4);
  EXPECT_EQ(no_modes.cols(), 0);
  const Eigen::MatrixXd no_nodes = root.ReadMatrix("no_nodes");
  EXPECT_EQ(no_nodes.rows(), 0);
  EXPECT_EQ(no_nodes.cols(), 3);
  EXPECT_EQ(root.ReadVector("no_frequencies").size(), 0);
  EXPECT_TRUE(root.ReadIntegers("no_ids").empty());
  EXPECT_TRUE(root.ReadStrings("no_names").empty());
}

TEST_F(H5FileTest, VectorIsOneDimensionalAndRoundTripsExactly) {
  const fs::path path = dir_ / "vector.h5";
  Eigen::VectorXd frequency_hz(4);
  frequency_hz << 0.1, 1.0 / 3.0, 1e300, -2.5e-310;
  {
    File file = File::Create(path);
    file.root().WriteVector("frequency_hz", frequency_hz, "Hz");
    file.Commit();
  }
  const File file = File::Open(path);
  EXPECT_EQ(file.root().Shape("frequency_hz"), (std::vector<std::int64_t>{4}));
  EXPECT_TRUE(file.root().ReadVector("frequency_hz") == frequency_hz);
}

TEST_F(H5FileTest, ScalarIsAScalarDatasetAndRoundTripsExactly) {
  const fs::path path = dir_ / "scalar.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteScalar("mass", 1.0 / 3.0, "kg");
    root.WriteScalar("not_a_number", std::numeric_limits<double>::quiet_NaN(), "1");
    file.Commit();
  }
  const File file = File::Open(path);
  EXPECT_TRUE(file.root().Shape("mass").empty());
  EXPECT_EQ(file.root().ReadScalar("mass"), 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(file.root().ReadScalar("not_a_number")));
}

TEST_F(H5FileTest, IntegersRoundTripFromAnyIntegerRangeIncludingInt64Extremes) {
  const fs::path path = dir_ / "integers.h5";
  const std::vector<std::int64_t> extremes = {std::numeric_limits<std::int64_t>::min(), -1, 0,
                                              std::numeric_limits<std::int64_t>::max()};
  const std::vector<int> small = {-7, 0, 42};
  const std::vector<Eigen::Index> indices = {5, 4, 3};
  const std::array<unsigned, 2> unsigned_values = {1u, 4000000000u};
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteIntegers("extremes", std::span<const std::int64_t>(extremes), "1");
    root.WriteIntegers("small", small, "1");
    root.WriteIntegers("indices", indices, "1");
    root.WriteIntegers("unsigned", unsigned_values, "1");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(root.ReadIntegers("extremes"), extremes);
  EXPECT_EQ(root.ReadIntegers("small"), (std::vector<std::int64_t>{-7, 0, 42}));
  EXPECT_EQ(root.ReadIntegers("indices"), (std::vector<std::int64_t>{5, 4, 3}));
  EXPECT_EQ(root.ReadIntegers("unsigned"), (std::vector<std::int64_t>{1, 4000000000}));
}

TEST_F(H5FileTest, IntegerMatrixRoundTripsWithDimsRowsThenCols) {
  const fs::path path = dir_ / "faces.h5";
  IntegerMatrix faces(2, 3);
  faces << 0, 1, 2, 2, 3, 0;
  {
    File file = File::Create(path);
    file.root().WriteIntegerMatrix("faces", faces, "1");
    file.Commit();
  }
  const File file = File::Open(path);
  EXPECT_EQ(file.root().Shape("faces"), (std::vector<std::int64_t>{2, 3}));
  EXPECT_TRUE(file.root().ReadIntegerMatrix("faces") == faces);
}

TEST_F(H5FileTest, StringsRoundTripAsUtf8IncludingEmptyOnes) {
  const fs::path path = dir_ / "strings.h5";
  const std::vector<std::string> names = {"normal", "", "\xC2\xB5m", "\xCE\xA9 mode 3",
                                          std::string(1000, 'x')};
  {
    File file = File::Create(path);
    file.root().WriteStrings("mode_kinds", names);
    file.Commit();
  }
  const File file = File::Open(path);
  EXPECT_EQ(file.root().Shape("mode_kinds"), (std::vector<std::int64_t>{5}));
  EXPECT_EQ(file.root().ReadStrings("mode_kinds"), names);
}

TEST_F(H5FileTest, EveryNumericDatasetCarriesItsUnits) {
  const fs::path path = dir_ / "units.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteMatrix("Phi", Eigen::MatrixXd::Identity(2, 2), "1");
    root.WriteVector("frequency_hz", Eigen::VectorXd::Ones(2), "Hz");
    root.WriteScalar("mass", 2.0, "kg");
    root.WriteIntegers("node_ids", std::vector<int>{1, 2}, "1");
    root.WriteIntegerMatrix("faces", IntegerMatrix::Zero(1, 3), "1");
    root.CreateAppendable("time", {}, "s").AppendRow(0.0);
    root.WriteStrings("names", {"a"});
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(root.ReadUnits("Phi"), "1");
  EXPECT_EQ(root.ReadUnits("frequency_hz"), "Hz");
  EXPECT_EQ(root.ReadUnits("mass"), "kg");
  EXPECT_EQ(root.ReadUnits("node_ids"), "1");
  EXPECT_EQ(root.ReadUnits("faces"), "1");
  EXPECT_EQ(root.ReadUnits("time"), "s");
  EXPECT_NO_THROW(root.RequireUnits("mass", "kg"));
  const std::string no_units = InputErrorOf([&] { (void)root.ReadUnits("names"); });
  EXPECT_EQ(no_units, path.string() + ": /names: no attribute 'units'");
}

TEST_F(H5FileTest, RequireUnitsNamesFoundAndExpectedUnits) {
  const fs::path path = dir_ / "units.h5";
  {
    File file = File::Create(path);
    file.root().CreateGroup("nodes").WriteMatrix("origin", Eigen::MatrixXd::Zero(2, 3), "mm");
    file.Commit();
  }
  const File file = File::Open(path);
  const std::string message =
      InputErrorOf([&] { file.root().OpenGroup("nodes").RequireUnits("origin", "m"); });
  EXPECT_EQ(message, path.string() + ": /nodes/origin: units 'mm', expected 'm'");
}

TEST_F(H5FileTest, EmptyUnitsAreRefusedAtWriteTime) {
  File file = File::Create(dir_ / "units.h5");
  Group root = file.root();
  EXPECT_THROW(root.WriteScalar("mass", 1.0, ""), InternalError);
  EXPECT_THROW(root.CreateAppendable("q", {2}, ""), InternalError);
}

TEST_F(H5FileTest, GroupAttributesRoundTripAndSettingAgainReplaces) {
  const fs::path path = dir_ / "attributes.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    root.SetIntegerAttribute("schema_version", 0);
    root.SetIntegerAttribute("schema_version", 1);  // replaces
    root.SetStringAttribute("tool", "flexmbs 0.1.0 \xE2\x80\x94 \xC2\xB5");
    root.SetStringAttribute("empty", "");
    Group provenance = root.CreateGroup("provenance");
    provenance.SetDoubleAttribute("residual_norm", 1.25e-13);
    provenance.SetIntegerAttribute("elements", -3);
    provenance.SetDoubleAttribute("residual_norm", 2.5e-13);  // replaces
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_TRUE(root.HasAttribute("schema_version"));
  EXPECT_FALSE(root.HasAttribute("absent"));
  EXPECT_EQ(root.GetIntegerAttribute("schema_version"), 1);
  EXPECT_EQ(root.GetStringAttribute("tool"), "flexmbs 0.1.0 \xE2\x80\x94 \xC2\xB5");
  EXPECT_EQ(root.GetStringAttribute("empty"), "");
  const Group provenance = root.OpenGroup("provenance");
  EXPECT_EQ(provenance.GetDoubleAttribute("residual_norm"), 2.5e-13);
  EXPECT_EQ(provenance.GetIntegerAttribute("elements"), -3);
}

TEST_F(H5FileTest, AttributeMissingOrOfAnotherKindIsAnInputErrorNamingIt) {
  const fs::path path = dir_ / "attributes.h5";
  {
    File file = File::Create(path);
    file.root().CreateGroup("refmod").SetStringAttribute("schema_version", "one");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group refmod = file.root().OpenGroup("refmod");
  EXPECT_EQ(InputErrorOf([&] { (void)refmod.GetIntegerAttribute("schema_version"); }),
            path.string() +
                ": /refmod: attribute 'schema_version': expected an integer, found a string");
  EXPECT_EQ(InputErrorOf([&] { (void)refmod.GetDoubleAttribute("mass"); }),
            path.string() + ": /refmod: no attribute 'mass'");
}

// ---------------------------------------------------------------------------------------------
// Structure

TEST_F(H5FileTest, GroupsNestAndListTheirChildrenSortedByName) {
  const fs::path path = dir_ / "groups.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    Group nodes = root.CreateGroup("nodes");
    nodes.CreateGroup("tip").WriteScalar("id", 7.0, "1");
    nodes.CreateGroup("base");
    root.WriteScalar("mass", 1.0, "kg");
    root.CreateGroup("refmod");
    EXPECT_EQ(nodes.path(), "/nodes");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(root.path(), "/");
  EXPECT_EQ(root.ChildNames(), (std::vector<std::string>{"mass", "nodes", "refmod"}));
  EXPECT_TRUE(root.Has("mass"));
  EXPECT_TRUE(root.HasDataset("mass"));
  EXPECT_FALSE(root.HasGroup("mass"));
  EXPECT_TRUE(root.HasGroup("nodes"));
  EXPECT_FALSE(root.Has("surfaces"));
  EXPECT_FALSE(root.HasGroup("surfaces"));
  const Group nodes = root.OpenGroup("nodes");
  EXPECT_EQ(nodes.ChildNames(), (std::vector<std::string>{"base", "tip"}));
  const Group tip = nodes.OpenGroup("tip");
  EXPECT_EQ(tip.path(), "/nodes/tip");
  EXPECT_EQ(tip.ReadScalar("id"), 7.0);
}

TEST_F(H5FileTest, OpeningAMissingGroupNamesItsFullPath) {
  const fs::path path = dir_ / "body.sid.h5";
  WriteFileWithMatrix(path);
  const File file = File::Open(path);
  const Group refmod = file.root().OpenGroup("refmod");
  const std::string missing = InputErrorOf([&] { (void)refmod.OpenGroup("nodes"); });
  EXPECT_EQ(missing, path.string() + ": /refmod/nodes: no such group");
  const std::string dataset = InputErrorOf([&] { (void)refmod.OpenGroup("M"); });
  EXPECT_EQ(dataset, path.string() + ": /refmod/M: is a dataset, expected a group");
}

TEST_F(H5FileTest, MisuseIsAnInternalError) {
  const fs::path path = dir_ / "misuse.h5";
  WriteFileWithMatrix(path);
  {
    File file = File::Create(dir_ / "other.h5");
    Group root = file.root();
    root.WriteScalar("mass", 1.0, "kg");
    EXPECT_THROW(root.WriteScalar("mass", 2.0, "kg"), InternalError) << "name written twice";
    EXPECT_THROW(root.CreateGroup("mass"), InternalError) << "name written twice";
    EXPECT_THROW(root.WriteScalar("a/b", 1.0, "kg"), InternalError) << "a path, not a name";
    EXPECT_THROW(root.WriteStrings("s", {std::string("a\0b", 3)}), InternalError);
  }
  const File file = File::Open(path);
  Group root = file.root();
  EXPECT_THROW(root.WriteScalar("mass", 1.0, "kg"), InternalError) << "file opened for reading";
}

// ---------------------------------------------------------------------------------------------
// The atomic-write guarantee

TEST_F(H5FileTest, CreateWithoutCommitLeavesNoFileAndNoTemporary) {
  {
    File file = File::Create(dir_ / "body.sid.h5");
    file.root().CreateGroup("refmod").WriteMatrix("M", NonSquareMatrix(), "kg");
    file.Flush();
    EXPECT_EQ(Entries().size(), 1u) << "the temporary exists while writing";
  }
  EXPECT_TRUE(Entries().empty());
}

TEST_F(H5FileTest, ExceptionWhileWritingLeavesNoFileAndNoTemporary) {
  const auto write = [&] {
    File file = File::Create(dir_ / "body.sid.h5");
    file.root().WriteScalar("mass", 1.0, "kg");
    throw std::runtime_error("meshing failed");
  };
  EXPECT_THROW(write(), std::runtime_error);
  EXPECT_TRUE(Entries().empty());
}

TEST_F(H5FileTest, CommitReplacesAnExistingFileOnlyWhenDone) {
  const fs::path path = dir_ / "body.sid.h5";
  {
    File file = File::Create(path);
    file.root().WriteScalar("version", 1.0, "1");
    file.Commit();
  }
  File writer = File::Create(path);
  writer.root().WriteScalar("version", 2.0, "1");
  writer.Flush();
  EXPECT_EQ(File::Open(path).root().ReadScalar("version"), 1.0) << "old content until Commit";
  writer.Commit();
  EXPECT_EQ(File::Open(path).root().ReadScalar("version"), 2.0);
  EXPECT_EQ(Entries(), (std::vector<std::string>{"body.sid.h5"})) << "no temporary left";
}

TEST_F(H5FileTest, HandlesThatOutliveCommitAreInertAndRefuseUse) {
  const fs::path path = dir_ / "body.sid.h5";
  File file = File::Create(path);
  Group root = file.root();
  Group refmod = root.CreateGroup("refmod");
  AppendableDataset time = root.CreateAppendable("time", {}, "s");
  time.AppendRow(0.0);
  file.Commit();  // while root, refmod and time are alive
  EXPECT_THROW(refmod.WriteScalar("mass", 1.0, "kg"), InternalError);
  EXPECT_THROW(time.AppendRow(1.0), InternalError);
  EXPECT_TRUE(File::Open(path).root().HasGroup("refmod"));
}

TEST_F(H5FileTest, CreateInAMissingFolderIsAnInputErrorNamingThePath) {
  const fs::path path = dir_ / "missing" / "body.sid.h5";
  const std::string message = InputErrorOf([&] { (void)File::Create(path); });
  EXPECT_TRUE(IsOneLine(message)) << message;
  EXPECT_EQ(message.rfind(path.string() + ": cannot create the file", 0), 0u) << message;
}

// ---------------------------------------------------------------------------------------------
// Bad files and bad reads: one-line InputErrors naming the path

TEST_F(H5FileTest, OpeningAMissingFileSaysNoSuchFile) {
  const fs::path path = dir_ / "absent.sid.h5";
  EXPECT_EQ(InputErrorOf([&] { (void)File::Open(path); }), path.string() + ": no such file");
}

TEST_F(H5FileTest, OpeningANonHdf5FileSaysNotAnHdf5File) {
  const fs::path text = dir_ / "body.sid.h5";
  std::ofstream(text) << "refmod:\n  mass: 1.0\n";
  EXPECT_EQ(InputErrorOf([&] { (void)File::Open(text); }), text.string() + ": not an HDF5 file");
  const fs::path empty = dir_ / "empty.sid.h5";
  std::ofstream{empty};
  EXPECT_EQ(InputErrorOf([&] { (void)File::Open(empty); }), empty.string() + ": not an HDF5 file");
}

TEST_F(H5FileTest, OpeningATruncatedFileSaysTruncatedOrCorrupt) {
  const fs::path path = dir_ / "body.sid.h5";
  {
    File file = File::Create(path);
    file.root().WriteMatrix("K", Eigen::MatrixXd::Random(40, 40), "N/m");
    file.Commit();
  }
  fs::resize_file(path, fs::file_size(path) / 2);
  const std::string message = InputErrorOf([&] { (void)File::Open(path); });
  EXPECT_TRUE(IsOneLine(message)) << message;
  EXPECT_EQ(message.rfind(path.string() + ": truncated or corrupt HDF5 file", 0), 0u) << message;
}

TEST_F(H5FileTest, ReadingAMissingDatasetNamesFileAndObjectPath) {
  const fs::path path = dir_ / "body.sid.h5";
  WriteFileWithMatrix(path);
  const File file = File::Open(path);
  const Group refmod = file.root().OpenGroup("refmod");
  EXPECT_EQ(InputErrorOf([&] { (void)refmod.ReadVector("frequency_hz"); }),
            path.string() + ": /refmod/frequency_hz: no such dataset");
  EXPECT_EQ(InputErrorOf([&] { (void)file.root().ReadMatrix("refmod"); }),
            path.string() + ": /refmod: is a group, expected a dataset");
}

TEST_F(H5FileTest, ReadingWithTheWrongRankNamesExpectedAndFoundRank) {
  const fs::path path = dir_ / "body.sid.h5";
  {
    File file = File::Create(path);
    file.root().CreateGroup("refmod").WriteMatrix("frequency_hz", Eigen::MatrixXd::Ones(2, 3),
                                                  "Hz");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group refmod = file.root().OpenGroup("refmod");
  EXPECT_EQ(InputErrorOf([&] { (void)refmod.ReadVector("frequency_hz"); }),
            path.string() +
                ": /refmod/frequency_hz: expected a 1-D dataset of doubles, found 2-D");
  EXPECT_EQ(InputErrorOf([&] { (void)refmod.ReadScalar("frequency_hz"); }),
            path.string() +
                ": /refmod/frequency_hz: expected a scalar dataset of doubles, found 2-D");
}

TEST_F(H5FileTest, ReadingWithTheWrongTypeNamesBothTypes) {
  const fs::path path = dir_ / "body.sid.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    root.WriteStrings("names", {"a", "b"});
    root.WriteIntegers("ids", std::vector<int>{1, 2}, "1");
    root.WriteScalar("mass", 1.0, "kg");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(InputErrorOf([&] { (void)root.ReadVector("names"); }),
            path.string() +
                ": /names: expected a 1-D dataset of doubles, found a 1-D dataset of strings");
  EXPECT_EQ(InputErrorOf([&] { (void)root.ReadVector("ids"); }),
            path.string() +
                ": /ids: expected a 1-D dataset of doubles, found a 1-D dataset of integers");
  EXPECT_EQ(InputErrorOf([&] { (void)root.ReadIntegers("mass"); }),
            path.string() +
                ": /mass: expected a 1-D dataset of integers, found a scalar dataset of doubles");
}

TEST_F(H5FileTest, FailuresPrintNothingOnStderr) {
  const fs::path path = dir_ / "body.sid.h5";
  WriteFileWithMatrix(path);
  const fs::path truncated = dir_ / "truncated.sid.h5";
  fs::copy_file(path, truncated);
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const fs::path text = dir_ / "text.sid.h5";
  std::ofstream(text) << "not hdf5";

  ::testing::internal::CaptureStderr();
  (void)InputErrorOf([&] { (void)File::Open(truncated); });
  (void)InputErrorOf([&] { (void)File::Open(text); });
  (void)InputErrorOf([&] { (void)File::Open(path).root().ReadVector("absent"); });
  (void)InputErrorOf([&] { (void)File::Open(path).root().OpenGroup("refmod").ReadVector("M"); });
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// ---------------------------------------------------------------------------------------------
// Appendable datasets and killed writers

Eigen::Vector3d StateRow(int step) { return Eigen::Vector3d(step, step + 0.25, -step / 3.0); }

TEST_F(H5FileTest, AppendableDatasetGrowsByRowsOfTheGivenShape) {
  const fs::path path = dir_ / "results.h5";
  {
    File file = File::Create(path);
    Group root = file.root();
    AppendableDataset time = root.CreateAppendable("time", {}, "s");
    AppendableDataset q = root.CreateAppendable("q", {3}, "m");
    AppendableDataset forces = root.CreateAppendable("forces", {2, 2}, "N");
    for (int step = 0; step < 5000; ++step) {  // more rows than one chunk holds
      time.AppendRow(step * 1e-3);
      q.AppendRow(StateRow(step));
      const std::array<double, 4> f = {1.0 * step, 2.0, 3.0, 4.0};  // row-major 2x2
      forces.AppendRow(f);
    }
    EXPECT_EQ(q.rows(), 5000);
    EXPECT_EQ(q.path(), "/q");
    file.Commit();
  }
  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(root.Shape("time"), (std::vector<std::int64_t>{5000}));
  EXPECT_EQ(root.Shape("q"), (std::vector<std::int64_t>{5000, 3}));
  EXPECT_EQ(root.Shape("forces"), (std::vector<std::int64_t>{5000, 2, 2}));
  const Eigen::VectorXd time = root.ReadVector("time");
  const Eigen::MatrixXd q = root.ReadMatrix("q");
  for (int step = 0; step < 5000; ++step) {
    ASSERT_EQ(time(step), step * 1e-3);
    ASSERT_TRUE(q.row(step) == StateRow(step).transpose()) << "step " << step;
  }
  EXPECT_EQ(root.ReadUnits("forces"), "N");
}

TEST_F(H5FileTest, AppendingARowOfTheWrongShapeIsAnInternalError) {
  File file = File::Create(dir_ / "results.h5");
  Group root = file.root();
  AppendableDataset q = root.CreateAppendable("q", {3}, "m");
  EXPECT_THROW(q.AppendRow(Eigen::VectorXd::Zero(2)), InternalError);
  EXPECT_THROW(q.AppendRow(1.0), InternalError);
  EXPECT_EQ(q.rows(), 0);
}

/// Forks; the child runs `write(ready)`, where `ready` tells the parent and then waits forever
/// with the files still open. Once the child is ready, the parent runs `while_alive` and then
/// kills the child with SIGKILL.
template <typename Write, typename WhileAlive>
void RunWriterAndKillIt(Write write, WhileAlive while_alive) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(fds[0]);
    const auto ready = [fd = fds[1]] {
      const char byte = 'r';
      if (::write(fd, &byte, 1) != 1) ::_exit(4);
      for (;;) ::pause();
    };
    try {
      write(ready);
    } catch (...) {
    }
    ::_exit(3);  // the writer failed before it was ready
  }
  ::close(fds[1]);
  char byte = 0;
  const ssize_t got = ::read(fds[0], &byte, 1);
  ::close(fds[0]);
  if (got == 1) while_alive();
  ::kill(pid, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_EQ(got, 1) << "the writer failed before it was ready";
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
}

template <typename Write>
void RunWriterAndKillIt(Write write) {
  RunWriterAndKillIt(write, [] {});
}

TEST_F(H5FileTest, RowsFlushedBeforeTheWriterIsKilledStayReadable) {
  constexpr int kFlushedRows = 7;
  const fs::path path = dir_ / "results.h5";
  RunWriterAndKillIt([&](const auto& ready) {
    File file = File::Create(path, WriteMode::kInPlace);
    Group root = file.root();
    root.SetStringAttribute("status", "running");
    AppendableDataset time = root.CreateAppendable("time", {}, "s");
    AppendableDataset q = root.CreateAppendable("q", {3}, "m");
    for (int step = 0; step < kFlushedRows; ++step) {
      time.AppendRow(0.5 * step);
      q.AppendRow(StateRow(step));
      q.Flush();
    }
    time.AppendRow(0.5 * kFlushedRows);  // appended but not flushed when the kill comes
    q.AppendRow(StateRow(kFlushedRows));
    ready();
  });

  const File file = File::Open(path);
  const Group root = file.root();
  EXPECT_EQ(root.GetStringAttribute("status"), "running");
  const Eigen::VectorXd time = root.ReadVector("time");
  const Eigen::MatrixXd q = root.ReadMatrix("q");
  ASSERT_GE(time.size(), kFlushedRows);
  ASSERT_GE(q.rows(), kFlushedRows);
  for (int step = 0; step < kFlushedRows; ++step) {
    EXPECT_EQ(time(step), 0.5 * step);
    EXPECT_TRUE(q.row(step) == StateRow(step).transpose()) << "step " << step;
  }
  EXPECT_EQ(root.ReadUnits("q"), "m");
}

TEST_F(H5FileTest, KillingAnAtomicWriterLeavesThePreviousFileIntact) {
  const fs::path path = dir_ / "body.sid.h5";
  {
    File file = File::Create(path);
    file.root().WriteScalar("version", 1.0, "1");
    file.Commit();
  }
  RunWriterAndKillIt([&](const auto& ready) {
    File file = File::Create(path);
    file.root().WriteScalar("version", 2.0, "1");
    file.root().WriteMatrix("K", Eigen::MatrixXd::Ones(200, 200), "N/m");
    file.Flush();
    ready();
  });
  const File file = File::Open(path);
  EXPECT_EQ(file.root().ReadScalar("version"), 1.0);
  EXPECT_FALSE(file.root().Has("K"));
}

TEST_F(H5FileTest, OpeningAFileAnotherProcessIsWritingSaysSo) {
  if (const char* locking = std::getenv("HDF5_USE_FILE_LOCKING");
      locking != nullptr && std::string(locking) != "TRUE" && std::string(locking) != "1") {
    GTEST_SKIP() << "HDF5 file locking is turned off (HDF5_USE_FILE_LOCKING=" << locking << ")";
  }
  const fs::path path = dir_ / "results.h5";
  std::string message;
  RunWriterAndKillIt(
      [&](const auto& ready) {
        File file = File::Create(path, WriteMode::kInPlace);
        file.root().CreateAppendable("time", {}, "s").AppendRow(0.0);
        file.Flush();
        ready();
      },
      [&] { message = InputErrorOf([&] { (void)File::Open(path); }); });
  EXPECT_EQ(message.rfind(path.string() + ": cannot open: another process is writing it", 0), 0u)
      << message;
  EXPECT_TRUE(IsOneLine(message)) << message;
}

// ---------------------------------------------------------------------------------------------
// What other tools see: h5py (an independent reader and writer)

bool SystemH5pyAvailable() {
  return std::system((std::string(kSystemPython) + " -c 'import h5py' >/dev/null 2>&1").c_str()) ==
         0;
}

/// Runs `script` with /usr/bin/python3 and `argument`; returns its exit status and output.
std::pair<int, std::string> RunPython(const fs::path& script_path, const std::string& script,
                                      const fs::path& argument) {
  std::ofstream(script_path) << script;
  const std::string command = std::string(kSystemPython) + " '" + script_path.string() + "' '" +
                              argument.string() + "' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  std::string output;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
    output += buffer.data();
  }
  return {::pclose(pipe), output};
}

TEST_F(H5FileTest, H5pySeesNaturalShapesUnitsAndUtf8Strings) {
  if (!SystemH5pyAvailable()) GTEST_SKIP() << "h5py is not installed for " << kSystemPython;
  const fs::path path = dir_ / "body.sid.h5";
  {
    Eigen::MatrixXd m(3, 5);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 5; ++c) m(r, c) = r + c / 7.0;
    }
    File file = File::Create(path);
    Group root = file.root();
    root.SetStringAttribute("tool", "flexmbs");
    Group body = root.CreateGroup("body");
    body.SetIntegerAttribute("schema_version", 1);
    body.SetDoubleAttribute("g", 9.81);
    body.WriteMatrix("M", m, "m");
    body.WriteVector("v", Eigen::Vector4d(0.1, 0.2, 0.3, 0.4), "Hz");
    body.WriteScalar("mass", 0.1, "kg");
    body.WriteIntegers("ids", std::vector<int>{3, -1, 7}, "1");
    body.WriteStrings("names", {"a", "\xC2\xB5m", ""});
    AppendableDataset q = root.CreateAppendable("q", {3}, "m");
    q.AppendRow(Eigen::Vector3d(1, 2, 3));
    q.AppendRow(Eigen::Vector3d(4, 5, 6));
    file.Commit();
  }
  const std::string script = R"PY(
import sys
import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
assert f.attrs["tool"] == "flexmbs", f.attrs["tool"]
body = f["body"]
assert body.attrs["schema_version"] == 1 and body.attrs["schema_version"].dtype == np.int64
assert body.attrs["g"] == 9.81
m = body["M"]
assert m.shape == (3, 5), m.shape
assert m.dtype == np.float64, m.dtype
expected = np.array([[r + c / 7.0 for c in range(5)] for r in range(3)])
assert (m[()] == expected).all(), m[()]
assert m.attrs["units"] == "m", m.attrs["units"]
assert body["v"].shape == (4,) and (body["v"][()] == [0.1, 0.2, 0.3, 0.4]).all()
assert body["v"].attrs["units"] == "Hz"
assert body["mass"].shape == () and body["mass"][()] == 0.1
ids = body["ids"]
assert ids.dtype == np.int64 and list(ids[()]) == [3, -1, 7], ids[()]
names = body["names"]
info = h5py.check_string_dtype(names.dtype)
assert info is not None and info.encoding == "utf-8" and info.length is None, info
assert list(names.asstr()[()]) == ["a", "\u00b5m", ""], names.asstr()[()]
q = f["q"]
assert q.shape == (2, 3) and q.maxshape == (None, 3) and q.chunks is not None
assert (q[()] == [[1, 2, 3], [4, 5, 6]]).all()
print("ok")
)PY";
  const auto [status, output] = RunPython(dir_ / "check.py", script, path);
  EXPECT_EQ(status, 0) << output;
  EXPECT_EQ(output, "ok\n");
}

TEST_F(H5FileTest, FilesWrittenByH5pyReadBackExactly) {
  if (!SystemH5pyAvailable()) GTEST_SKIP() << "h5py is not installed for " << kSystemPython;
  const fs::path path = dir_ / "from_h5py.h5";
  const std::string script = R"PY(
import sys
import h5py
import numpy as np

with h5py.File(sys.argv[1], "w") as f:
    f["M"] = np.array([[r + c / 7.0 for c in range(4)] for r in range(2)])
    f["M"].attrs["units"] = "N"
    f["ids32"] = np.array([3, -1, 7], dtype=np.int32)
    f["half"] = np.float32(1.5)
    f.create_dataset("names", data=["alpha", "\u03b2eta"], dtype=h5py.string_dtype())
    f["fixed"] = np.array([b"ab", b"cde"])
    f.attrs["title"] = "h\u00e9llo"
    f.attrs["n"] = 42
    f.attrs["x"] = 2.5
print("ok")
)PY";
  const auto [status, output] = RunPython(dir_ / "write.py", script, path);
  ASSERT_EQ(status, 0) << output;

  const File file = File::Open(path);
  const Group root = file.root();
  Eigen::MatrixXd expected(2, 4);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 4; ++c) expected(r, c) = r + c / 7.0;
  }
  EXPECT_TRUE(root.ReadMatrix("M") == expected) << root.ReadMatrix("M");
  EXPECT_EQ(root.ReadUnits("M"), "N");
  EXPECT_EQ(root.ReadIntegers("ids32"), (std::vector<std::int64_t>{3, -1, 7}));
  EXPECT_EQ(root.ReadScalar("half"), 1.5);
  EXPECT_EQ(root.ReadStrings("names"), (std::vector<std::string>{"alpha", "\xCE\xB2" "eta"}));
  EXPECT_EQ(root.ReadStrings("fixed"), (std::vector<std::string>{"ab", "cde"}));
  EXPECT_EQ(root.GetStringAttribute("title"), "h\xC3\xA9llo");
  EXPECT_EQ(root.GetIntegerAttribute("n"), 42);
  EXPECT_EQ(root.GetDoubleAttribute("x"), 2.5);
}

}  // namespace
}  // namespace flexmbs::h5
