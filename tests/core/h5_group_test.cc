// core/h5_file.h, Group: exact round trips of every dataset kind, units, attributes and
// the group structure.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/h5_file.h"
#include "tests/core/h5_test_support.h"

namespace flexmbs::h5 {
namespace {

namespace fs = std::filesystem;
using testing::H5FileTest;
using testing::InputErrorOf;
using testing::NonSquareMatrix;
using testing::WriteFileWithMatrix;

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

TEST_F(H5FileTest, TallMatrixRoundTripsExactlyOverSeveralChunksAndTransposeBands) {
  // 70001 x 3 doubles: chunks of 43690 rows (about 1 MiB), one full and one partial, written
  // with flexmbs's Fletcher32 and read through HDF5's filter, which checks it; 274 transpose
  // bands of 256 rows, the last one partial.
  const fs::path path = dir_ / "tall.h5";
  const Eigen::MatrixXd written = Eigen::MatrixXd::Random(70001, 3);
  {
    File file = File::Create(path);
    file.root().WriteMatrix("phi", written, "m/q");
    file.Commit();
  }
  const Eigen::MatrixXd read = File::Open(path).root().ReadMatrix("phi");
  ASSERT_EQ(read.rows(), 70001);
  ASSERT_EQ(read.cols(), 3);
  EXPECT_TRUE(read == written);
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

}  // namespace
}  // namespace flexmbs::h5
