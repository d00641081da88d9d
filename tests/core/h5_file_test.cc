// core/h5_file.h, File: the atomic-write guarantee, and one-line InputErrors naming the path
// for bad files and bad reads.

#include "core/h5_file.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/core/h5_test_support.h"

namespace flexmbs::h5 {
namespace {

namespace fs = std::filesystem;
using testing::H5FileTest;
using testing::InputErrorOf;
using testing::IsOneLine;
using testing::NonSquareMatrix;
using testing::WriteFileWithMatrix;

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

}  // namespace
}  // namespace flexmbs::h5
