// core/h5_file.h, AppendableDataset: datasets that grow by rows, writers killed while writing;
// and what h5py, an independent reader and writer, sees of our files and we of its.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/h5_file.h"
#include "tests/core/h5_test_support.h"

namespace flexmbs::h5 {
namespace {

namespace fs = std::filesystem;
using testing::H5FileTest;
using testing::InputErrorOf;
using testing::IsOneLine;

// Debian's Python packages (h5py) are seen only by this interpreter (STACK.md).
constexpr const char* kSystemPython = "/usr/bin/python3";

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

// Files written in place carry per dataset the XXH3-128 of its values as stored (attributes
// xxh3_128, xxh3_128_rows), for rows appended and flushed as for datasets written whole: h5py and
// python3-xxhash compute the same from the file. Files written before carried a SHA-256 (sha256,
// sha256_rows): one made so by h5py reads back, one whose SHA-256 or XXH3-128 does not match
// its values is refused by name.
TEST_F(H5FileTest, InPlaceDatasetsCarryTheXxh3OfTheirValuesAndAnEarlierSha256IsStillChecked) {
  if (!SystemH5pyAvailable()) GTEST_SKIP() << "h5py is not installed for " << kSystemPython;
  const fs::path path = dir_ / "results.h5";
  const Eigen::MatrixXd K = Eigen::MatrixXd::Random(40, 7);
  {
    File file = File::Create(path, WriteMode::kInPlace);
    Group root = file.root();
    AppendableDataset q = root.CreateAppendable("q", {3}, "m");
    for (int step = 0; step < 5; ++step) {
      q.AppendRow(StateRow(step));
      if (step == 2) q.Flush();
    }
    root.WriteMatrix("K", K, "N/m");
    root.WriteMatrix("old_K", K, "N/m");
    root.WriteMatrix("bad_K", K, "N/m");
    file.Commit();
  }
  const std::string script = R"(import sys, hashlib, h5py, numpy, xxhash
f = h5py.File(sys.argv[1], 'r+')
for name in ('q', 'K'):
    d = f[name]
    values = d[()].astype('<f8').tobytes()
    assert d.attrs['xxh3_128'].decode() == xxhash.xxh3_128_hexdigest(values), name
    assert int(d.attrs['xxh3_128_rows']) == d.shape[0], (name, int(d.attrs['xxh3_128_rows']))
def sha256_instead(name, values):
    d = f[name]
    del d.attrs['xxh3_128']
    del d.attrs['xxh3_128_rows']
    d.attrs['sha256'] = numpy.bytes_(hashlib.sha256(values).hexdigest())
    d.attrs['sha256_rows'] = numpy.int64(d.shape[0])
sha256_instead('old_K', f['old_K'][()].astype('<f8').tobytes())
changed = f['q'][()].astype('<f8')
changed[1, 2] += 1.0
sha256_instead('q', changed.tobytes())
changed = f['bad_K'][()].astype('<f8')
changed[0, 0] *= -1.0
f['bad_K'].attrs['xxh3_128'] = numpy.bytes_(xxhash.xxh3_128_hexdigest(changed.tobytes()))
f.close()
print('ok')
)";
  const auto [status, output] = RunPython(dir_ / "digests.py", script, path);
  ASSERT_EQ(status, 0) << output;
  ASSERT_EQ(output, "ok\n");
  const File file = File::Open(path);
  EXPECT_TRUE(file.root().ReadMatrix("K") == K);
  EXPECT_TRUE(file.root().ReadMatrix("old_K") == K);
  EXPECT_EQ(InputErrorOf([&] { file.root().ReadMatrix("q"); }),
            path.string() + ": /q: the values do not match their SHA-256: the file is damaged");
  EXPECT_EQ(InputErrorOf([&] { file.root().ReadMatrix("bad_K"); }),
            path.string() + ": /bad_K: the values do not match their XXH3-128: the file is damaged");
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
assert f.attrs["tool"] == b"flexmbs", f.attrs["tool"]
body = f["body"]
assert body.attrs["schema_version"] == 1 and body.attrs["schema_version"].dtype == np.int64
assert body.attrs["g"] == 9.81
m = body["M"]
assert m.shape == (3, 5), m.shape
assert m.dtype == np.float64, m.dtype
expected = np.array([[r + c / 7.0 for c in range(5)] for r in range(3)])
assert (m[()] == expected).all(), m[()]
assert m.attrs["units"] == b"m", m.attrs["units"]
assert m.fletcher32 and m.chunks == (3, 5), (m.fletcher32, m.chunks)
assert body["v"].shape == (4,) and (body["v"][()] == [0.1, 0.2, 0.3, 0.4]).all()
assert body["v"].attrs["units"] == b"Hz"
assert body["mass"].shape == () and body["mass"][()] == 0.1
ids = body["ids"]
assert ids.dtype == np.int64 and list(ids[()]) == [3, -1, 7], ids[()]
names = body["names"]
info = h5py.check_string_dtype(names.dtype)
assert info is not None and info.encoding == "utf-8" and info.length == 3, info
assert list(names.asstr()[()]) == ["a", "\u00b5m", ""], names.asstr()[()]
q = f["q"]
assert q.shape == (2, 3) and q.maxshape == (None, 3) and q.chunks is not None and q.fletcher32
assert (q[()] == [[1, 2, 3], [4, 5, 6]]).all()
print("ok")
)PY";
  const auto [status, output] = RunPython(dir_ / "check.py", script, path);
  EXPECT_EQ(status, 0) << output;
  EXPECT_EQ(output, "ok\n");
}

// h5py's defaults are not all what flexmbs reads: binary64, int64 and fixed-length strings read
// back exactly; other widths and variable-length strings (HDF5's global heap, which a damaged
// file can make HDF5 read out of bounds) are refused with one line naming the object.
TEST_F(H5FileTest, FilesWrittenByH5pyReadBackExactlyOrAreRefusedByType) {
  if (!SystemH5pyAvailable()) GTEST_SKIP() << "h5py is not installed for " << kSystemPython;
  const fs::path path = dir_ / "from_h5py.h5";
  const std::string script = R"PY(
import sys
import h5py
import numpy as np

with h5py.File(sys.argv[1], "w") as f:
    f["M"] = np.array([[r + c / 7.0 for c in range(4)] for r in range(2)])
    f["M"].attrs["units"] = np.bytes_("N")
    f["ids32"] = np.array([3, -1, 7], dtype=np.int32)
    f["half"] = np.float32(1.5)
    f.create_dataset("names", data=["alpha", "\u03b2eta"], dtype=h5py.string_dtype())
    f["fixed"] = np.array([b"ab", b"cde"])
    f.attrs["title"] = np.bytes_("h\u00e9llo".encode())
    f.attrs["vlen_title"] = "h\u00e9llo"
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
  EXPECT_EQ(root.ReadStrings("fixed"), (std::vector<std::string>{"ab", "cde"}));
  EXPECT_EQ(root.GetStringAttribute("title"), "h\xC3\xA9llo");
  EXPECT_EQ(root.GetIntegerAttribute("n"), 42);
  EXPECT_EQ(root.GetDoubleAttribute("x"), 2.5);
  const std::string name = path.string();
  EXPECT_EQ(InputErrorOf([&] { (void)root.ReadIntegers("ids32"); }),
            name + ": /ids32: expected 8-byte signed integers, found 4-byte signed integers");
  EXPECT_EQ(InputErrorOf([&] { (void)root.ReadScalar("half"); }),
            name + ": /half: expected 8-byte IEEE doubles, found 4-byte floating-point values");
  EXPECT_NE(InputErrorOf([&] { (void)root.ReadStrings("names"); })
                .find(name + ": /names: variable-length strings are not read"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { (void)root.GetStringAttribute("vlen_title"); })
                .find(name + ": /: attribute 'vlen_title': variable-length strings are not read"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::h5
