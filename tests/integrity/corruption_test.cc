// Damaged `.sid.h5` bodies and results files (issue 21, docs/h5.md): a small body and a small
// results file are damaged byte by byte (one bit of every byte, or of a dense sample of 10,000
// bytes of metadata and 1,000 of data, flipped in turn), cut
// at every length class, and have their strings and attributes overwritten; each damaged copy
// is read in-process by the reader `flexmbs info --verify` runs (every value of the file). No
// copy may crash or hang the reader, and each one is either refused with one line naming the
// file or reads back exactly the values of the intact file (the digest of every value read is
// equal): a harmless damage, counted by the structure it hit and printed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mbs/results_file.h"
#include "sid/sid_digest.h"
#include "sid/sid_file.h"
#include "tests/integrity/file_damage.h"
#include "tests/sid/sample_body.h"

namespace flexmbs::testing {
namespace {

namespace fs = std::filesystem;

/// A folder of its own for each test, removed afterwards; in memory (/dev/shm) where there is
/// one, as the test writes tens of thousands of damaged copies.
class CorruptionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path memory = "/dev/shm";
    dir_ = (fs::is_directory(memory) ? memory : fs::temp_directory_path()) /
           fmt::format("flexmbs_corruption_{}_{}", ::getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The reader `flexmbs simulate` uses (digest checked): the digest of the body it returns and
/// its provenance, which the content digest leaves out.
std::string ReadBody(const fs::path& path) {
  const sid::ReducedBody body = sid::ReadReducedBody(path);
  std::string digest = sid::ContentDigest(body);
  for (const auto& [key, value] : body.provenance) digest += "\n" + key + "=" + value;
  return digest;
}

/// The reader of `flexmbs info --verify` for results files.
std::string ReadResults(const fs::path& path) { return mbs::VerifyResultsFile(path).content_sha256; }

fs::path WriteBody(const fs::path& dir) {
  const fs::path path = dir / "body.sid.h5";
  sid::WriteReducedBody(path, SampleBody());
  return path;
}

/// A finished run of a rigid and a flexible body (2 modes, a marker) and a joint, 20 samples.
fs::path WriteResults(const fs::path& dir) {
  const fs::path path = dir / "results.h5";
  mbs::ResultsLayout layout;
  layout.bodies = {{"crank", "rigid", {}, {}}, {"rod", "flexible", {"normal_1", "normal_2"}, {"tip"}}};
  layout.joints = {{"hinge", "revolute"}};
  layout.provenance = {{"scene_file", "scene.yaml"}};
  mbs::ResultsWriter writer(path, layout);
  for (int k = 0; k < 20; ++k) {
    mbs::ResultsSample sample;
    sample.time = 0.01 * k;
    sample.positions = {Eigen::VectorXd::Random(7), Eigen::VectorXd::Random(9)};
    sample.velocities = {Eigen::VectorXd::Random(6), Eigen::VectorXd::Random(8)};
    sample.marker_positions = {{}, {Eigen::Vector3d::Random()}};
    sample.joint_forces = {Eigen::Vector3d::Random()};
    sample.joint_torques = {Eigen::Vector3d::Random()};
    sample.kinetic_energy = k;
    writer.Append(sample);
  }
  writer.Finish("end time reached");
  return path;
}

/// Flips per file: every byte of a file up to this size; of a larger one, this many evenly
/// spaced bytes outside its data chunks (metadata: superblock, object headers, indexes, free
/// space) and a tenth as many inside them (the test stays near a minute).
constexpr std::size_t kDenseFlips = 10000;

/// Keep every FlipEvery()-th of the positions: FLEXMBS_FLIP_EVERY (default 1, all of them).
/// scripts/check-sanitizers.sh sets 7: under ASan a flip costs about 0.1 s (the body's 11322
/// took 19.5 min). Odd, so that the flipped bit (position mod 8) still takes every value.
std::size_t FlipEvery() {
  const char* every = std::getenv("FLEXMBS_FLIP_EVERY");
  const long value = every == nullptr ? 1 : std::strtol(every, nullptr, 10);
  return value >= 1 ? static_cast<std::size_t>(value) : 1;
}

/// The positions to flip in a file of `size` bytes with `map`: every byte, or kDenseFlips
/// evenly spaced ones outside the data chunks and kDenseFlips / 10 inside; then every
/// FlipEvery()-th of those.
std::vector<std::size_t> FlipPositions(std::size_t size, const std::vector<FileRegion>& map) {
  std::vector<std::size_t> metadata, data;
  for (std::size_t position = 0; position < size; ++position) {
    (RegionOf(map, position) == "data chunk" ? data : metadata).push_back(position);
  }
  std::vector<std::size_t> positions;
  if (size <= kDenseFlips) {
    positions = metadata;
    positions.insert(positions.end(), data.begin(), data.end());
  } else {
    for (const auto& [list, count] : {std::pair{&metadata, kDenseFlips}, std::pair{&data, kDenseFlips / 10}}) {
      const std::size_t step = std::max<std::size_t>(1, list->size() / count);
      for (std::size_t i = 0; i < list->size(); i += step) positions.push_back((*list)[i]);
    }
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < positions.size(); i += FlipEvery()) kept.push_back(positions[i]);
  return kept;
}

/// Flips bit (position mod 8) of each byte FlipPositions gives, one at a time, in place in a copy.
DamageTally FlipBytes(const fs::path& intact, const DigestReader& read) {
  const std::vector<FileRegion> map = MapFile(intact);
  const std::string digest = read(intact);
  const fs::path damaged = intact.parent_path() / ("damaged_" + intact.filename().string());
  fs::copy_file(intact, damaged, fs::copy_options::overwrite_existing);
  std::fstream file(damaged, std::ios::binary | std::ios::in | std::ios::out);
  DamageTally tally;
  for (const std::size_t position : FlipPositions(fs::file_size(intact), map)) {
    char byte = 0;
    file.seekg(static_cast<std::streamoff>(position)).read(&byte, 1);
    const char flipped = static_cast<char>(byte ^ (1 << (position % 8)));
    file.seekp(static_cast<std::streamoff>(position)).write(&flipped, 1).flush();
    ReadDamagedFile(damaged, {fmt::format("bit {} of byte {} flipped", position % 8, position), RegionOf(map, position)},
                    read, digest, tally);
    file.seekp(static_cast<std::streamoff>(position)).write(&byte, 1).flush();
  }
  return tally;
}

/// Cuts `intact` at every length class: every length within 8 bytes of a region's start or end
/// and of the file's ends, and about 2000 evenly spaced lengths in between.
DamageTally TruncateAtEveryLength(const fs::path& intact, const DigestReader& read) {
  const std::string original = Bytes(intact);
  const std::vector<FileRegion> map = MapFile(intact);
  const std::string digest = read(intact);
  const fs::path damaged = intact.parent_path() / ("truncated_" + intact.filename().string());
  DamageTally tally;
  for (std::size_t length = 0; length < original.size(); ++length) {
    bool near_boundary = length < 8 || original.size() - length <= 8;
    for (const FileRegion& region : map) {
      near_boundary = near_boundary || (length >= region.begin && length < region.begin + 8) ||
                      (length + 8 > region.end && length <= region.end);
    }
    if (!near_boundary && length % std::max<std::size_t>(1, original.size() / 2000) != 0) continue;
    ReadDamagedCopy(original.substr(0, length), damaged,
                    {fmt::format("cut to {} bytes", length), RegionOf(map, length)}, read, digest, tally);
  }
  return tally;
}

/// Overwrites every occurrence of each of `strings` in `intact` (its first byte with 'X', with
/// 0xFF, and the whole string with zeros): names, units and string values of datasets and
/// attributes.
DamageTally DamageStrings(const fs::path& intact, const std::vector<std::string>& strings, const DigestReader& read) {
  const std::string original = Bytes(intact);
  const std::vector<FileRegion> map = MapFile(intact);
  const std::string digest = read(intact);
  const fs::path damaged = intact.parent_path() / ("strings_" + intact.filename().string());
  DamageTally tally;
  for (const std::string& text : strings) {
    for (std::size_t at = original.find(text); at != std::string::npos; at = original.find(text, at + 1)) {
      for (const std::string& replacement : {std::string("X"), std::string("\xff"), std::string(text.size(), '\0')}) {
        std::string bytes = original;
        bytes.replace(at, replacement.size(), replacement);
        ReadDamagedCopy(bytes, damaged, {fmt::format("'{}' at byte {} overwritten", text, at), RegionOf(map, at)},
                        read, digest, tally);
      }
    }
  }
  return tally;
}

/// Prints the tally and fails the test for each damaged copy that was not refused or harmless.
void Report(const DamageTally& tally, const std::string& title) {
  std::cout << tally.Summary(title);
  EXPECT_GT(tally.refused, 0) << title;
  EXPECT_TRUE(tally.failures.empty()) << title << ": " << tally.failures.size() << " failures, the first: "
                                      << tally.failures.front();
  EXPECT_EQ(tally.harmless.count("data chunk"), 0u) << title << ": a damaged data chunk was not refused";
}

TEST_F(CorruptionTest, FlippedBytesOfABodyAreRefusedOrHarmless) {
  const fs::path body = WriteBody(dir_);
  Report(FlipBytes(body, &ReadBody), fmt::format("body ({} bytes), one bit flipped per byte", fs::file_size(body)));
}

TEST_F(CorruptionTest, FlippedBytesOfAResultsFileAreRefusedOrHarmless) {
  const fs::path results = WriteResults(dir_);
  Report(FlipBytes(results, &ReadResults),
         fmt::format("results ({} bytes), one bit flipped per byte", fs::file_size(results)));
}

TEST_F(CorruptionTest, TruncatedFilesAreRefused) {
  const fs::path body = WriteBody(dir_), results = WriteResults(dir_);
  const DamageTally body_tally = TruncateAtEveryLength(body, &ReadBody);
  const DamageTally results_tally = TruncateAtEveryLength(results, &ReadResults);
  Report(body_tally, "body cut short");
  Report(results_tally, "results cut short");
  EXPECT_EQ(body_tally.refused, body_tally.copies);
  EXPECT_EQ(results_tally.refused, results_tally.copies);
}

TEST_F(CorruptionTest, DamagedStringsAndAttributesAreRefusedOrHarmless) {
  const fs::path body = WriteBody(dir_), results = WriteResults(dir_);
  Report(DamageStrings(body, {"flexmbs-sid", "bracket", "normal_1", "constraint", "rigid", "modal 2 %", "kg m^2/q",
                              "m/q", "tip", "pad", "eigensolver", "spectra", "content_xxh3_128", "order", "units"},
                       &ReadBody),
         "body strings and attributes overwritten");
  Report(DamageStrings(results, {"flexmbs-results", "end time reached", "flexible", "revolute", "normal_2", "rad/s",
                                 "scene.yaml", "complete", "termination", "units", "xxh3_128"},
                       &ReadResults),
         "results strings and attributes overwritten");
}

}  // namespace
}  // namespace flexmbs::testing
