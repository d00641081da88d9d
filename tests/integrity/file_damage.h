#pragma once
// Damaging a file byte by byte and reading it back (tests/integrity/corruption_test.cc): the map
// of a file's HDF5 structures, and the tally of what each damaged copy gave.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace flexmbs::testing {

/// A byte range [begin, end) of a file and the HDF5 structure it holds.
struct FileRegion {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
  std::string kind;  ///< "superblock", "object header", "data chunk", "contiguous data", "after ..."
};

/// The superblock, every object header and every chunk of raw data of the HDF5 file `path`,
/// then every other structure found by its signature ("TREE", "FAHD", ...), up to the next one.
std::vector<FileRegion> MapFile(const std::filesystem::path& path);

/// What a byte position is part of: the kind of the first region holding it, or "no structure:
/// free space or padding between structures".
std::string RegionOf(const std::vector<FileRegion>& map, std::uint64_t position);

/// Reads a file and returns a digest of every value it returned; throws flexmbs::InputError.
using DigestReader = std::function<std::string(const std::filesystem::path&)>;

/// What the damaged copies of a file gave.
struct DamageTally {
  int copies = 0;
  int refused = 0;                         ///< one-line InputError naming the file
  std::map<std::string, int> harmless;     ///< read back unchanged, by the region of the damage
  std::vector<std::string> failures;       ///< accepted with changed values, or a bad message
  /// A few lines: counts and the harmless ones by region.
  std::string Summary(const std::string& title) const;
};

/// What was done to a damaged file ("bit 3 of byte 1234 flipped") and the region it hit.
struct Damage {
  std::string what;
  std::string where;
};

/// Reads the damaged file `damaged` with `read`, compares the digest with `intact_digest` and
/// counts the outcome (a harmless damage under its region).
void ReadDamagedFile(const std::filesystem::path& damaged, const Damage& damage, const DigestReader& read,
                     const std::string& intact_digest, DamageTally& tally);

/// Writes `bytes` to `damaged` and reads it as ReadDamagedFile does.
void ReadDamagedCopy(const std::string& bytes, const std::filesystem::path& damaged, const Damage& damage,
                     const DigestReader& read, const std::string& intact_digest, DamageTally& tally);

}  // namespace flexmbs::testing
