// core/h5_detail.h: the hash of a dataset's values in files written in place: XXH3-128 since
// 2026-11-27, SHA-256 before (still checked when a file has it).

#include <fmt/format.h>
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/h5_detail.h"
#include "core/sha256.h"
#include "core/xxh3.h"

namespace flexmbs::h5::detail {

namespace {

constexpr const char* kDigest = "xxh3_128";
constexpr const char* kDigestRows = "xxh3_128_rows";
/// The attributes of files written before, checked with SHA-256.
constexpr const char* kSha256Digest = "sha256";
constexpr const char* kSha256DigestRows = "sha256_rows";

/// The digest of the first `size` bytes at `bytes` with `Hash`.
template <typename Hash>
std::string HexDigestOf(const void* bytes, std::size_t size) {
  Hash hash;
  hash.Update(bytes, size);
  return hash.HexDigest();
}

}  // namespace

void WriteValuesDigest(const FileState& file, hid_t id, const std::string& object, const std::string& hex,
                       std::int64_t rows) {
  // Rewritten in place after the first time (same types and sizes), so that flushing a growing
  // dataset's digest every second leaves no stale attributes behind.
  const Handle text = Utf8StringType(hex.size());
  const auto write = [&](const char* name, hid_t type, const void* value) {
    const std::string what = fmt::format("write attribute '{}'", name);
    if (Check(H5Aexists(id, name), file, object, what) <= 0) {
      const Handle space(CheckInternal(H5Screate(H5S_SCALAR), "create a scalar dataspace"), H5Sclose);
      const Handle created(Check(H5Acreate2(id, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), file, object, what),
                           H5Aclose);
    }
    const Handle attribute(Check(H5Aopen(id, name, H5P_DEFAULT), file, object, what), H5Aclose);
    Check(H5Awrite(attribute.get(), type == H5T_STD_I64LE ? H5T_NATIVE_INT64 : type, value), file, object, what);
  };
  write(kDigest, text.get(), hex.data());
  write(kDigestRows, H5T_STD_I64LE, &rows);
}

void RecordRowDigests(FileState& file) {
  if (file.mode != WriteMode::kInPlace) return;
  std::erase_if(file.row_digests, [](const std::weak_ptr<RowsDigest>& d) { return d.expired(); });
  for (const std::weak_ptr<RowsDigest>& weak : file.row_digests) {
    const std::shared_ptr<RowsDigest> digest = weak.lock();
    WriteValuesDigest(file, digest->id, digest->object, digest->hash.HexDigest(), digest->rows);
  }
}

void WriteValuesDigestIfInPlace(const FileState& file, hid_t id, const std::string& object, const void* bytes,
                                std::size_t size, std::int64_t rows) {
  if (file.mode != WriteMode::kInPlace) return;
  WriteValuesDigest(file, id, object, HexDigestOf<Xxh3_128>(bytes, size), rows);
}

void CheckValuesDigest(const FileState& file, const DatasetView& view, const std::string& object, const void* bytes,
                       std::size_t row_bytes) {
  const hid_t id = view.dataset.get();
  const bool xxh3 = Check(H5Aexists(id, kDigest), file, object, "read the digest") > 0;
  if (!xxh3 && Check(H5Aexists(id, kSha256Digest), file, object, "read the digest") <= 0) return;
  const std::string stored = ReadStringAttribute(file, id, object, xxh3 ? kDigest : kSha256Digest);
  const std::int64_t rows = ReadIntegerAttribute(file, id, object, xxh3 ? kDigestRows : kSha256DigestRows);
  const std::uint64_t available = view.rank > 0 ? view.dims[0] : 1;
  if (rows < 0 || static_cast<std::uint64_t>(rows) > available) {
    Fail(file, object, fmt::format("its digest covers {} rows of {}", rows, available));
  }
  const std::size_t size = static_cast<std::size_t>(rows) * row_bytes;
  if ((xxh3 ? HexDigestOf<Xxh3_128>(bytes, size) : HexDigestOf<Sha256>(bytes, size)) != stored) {
    Fail(file, object, fmt::format("the values do not match their {}: the file is damaged", xxh3 ? "XXH3-128" : "SHA-256"));
  }
}

}  // namespace flexmbs::h5::detail
