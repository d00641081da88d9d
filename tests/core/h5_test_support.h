#pragma once

// Shared by the tests of core/h5_file.h (h5_group_test.cc, h5_file_test.cc,
// h5_appendable_test.cc): the H5FileTest fixture with a fresh folder per test, the message of an
// expected InputError, and a matrix whose round trip would show any loss.
//
// HDF5 stores IEEE-754 binary64 and two's-complement int64 verbatim, so every round trip in these
// tests is exact: values are compared with == (a tolerance of zero), never approximately. The
// same holds against h5py, which computes its expected values with the same IEEE operations.

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <system_error>
#include <vector>

#include "core/error.h"
#include "core/h5_file.h"

namespace flexmbs::h5::testing {

/// Gives each test an empty folder `dir_` of its own, removed afterwards.
class H5FileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = std::filesystem::temp_directory_path() /
           ("flexmbs_h5_test_" + std::to_string(::getpid()) + "_" + test);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  /// Names of the files in the test folder, sorted.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  std::filesystem::path dir_;
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

inline bool IsOneLine(const std::string& message) {
  return !message.empty() && message.find('\n') == std::string::npos;
}

/// A 3x5 matrix (non-square, so a transposed layout would show) with values that need all
/// 64 bits, and the extremes of binary64 in its last row.
inline Eigen::MatrixXd NonSquareMatrix() {
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

/// Writes NonSquareMatrix() as /refmod/M (units "kg") to a new file at `path`.
inline void WriteFileWithMatrix(const std::filesystem::path& path) {
  File file = File::Create(path);
  file.root().CreateGroup("refmod").WriteMatrix("M", NonSquareMatrix(), "kg");
  file.Commit();
}

}  // namespace flexmbs::h5::testing
