#pragma once

// Private to the core/h5_*.cc files: the state that File,
// Group and AppendableDataset of one file share, HDF5 handles, and the error and naming helpers
// the three use. Not included by core/h5_file.h, so no HDF5 header reaches flexmbs' users.

#include <fmt/format.h>
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/h5_file.h"
#include "core/xxh3.h"

static_assert(std::is_same_v<hid_t, std::int64_t>, "h5_file.h stores hid_t as std::int64_t");

namespace flexmbs::h5::detail {

/// The running XXH3-128 of an appendable dataset's rows, shared by the dataset and its file,
/// which records it at every Flush and at Commit (files written in place).
struct RowsDigest {
  hid_t id = H5I_INVALID_HID;
  std::string object;
  std::int64_t rows = 0;
  Xxh3_128 hash;
};

/// What File, Group and AppendableDataset of one file share. Groups and datasets check `open`
/// before closing their ids: File closes with H5F_CLOSE_STRONG, which closes them all.
struct FileState {
  std::filesystem::path path;       // as given by the caller; named in every message
  std::filesystem::path disk_path;  // where HDF5 writes: the temporary (kAtomic) or `path`
  WriteMode mode = WriteMode::kAtomic;
  bool writable = false;
  bool open = false;
  hid_t id = H5I_INVALID_HID;
  std::vector<std::weak_ptr<RowsDigest>> row_digests;  // of the appendable datasets

  std::string name() const { return path.string(); }
};

// ------------------------------------------------------------------------------------------
// HDF5 errors and handles (defined in h5_file.cc)

/// The messages of HDF5's error stack for the last failed call, innermost (most specific)
/// first; clears the stack.
std::vector<std::string> TakeErrorStack();

/// "HDF5: <innermost message>" for the last failed call, to put in parentheses.
std::string Hdf5Detail();

/// Throws InputError "<file>: <problem>".
[[noreturn]] void FailFile(const FileState& file, std::string_view problem);

/// Throws InputError "<file>: <object>: <problem>".
[[noreturn]] void Fail(const FileState& file, std::string_view object, std::string_view problem);

/// Returns `result` unless it is negative (HDF5's failure), else throws InputError
/// "<file>: <object>: cannot <action> (HDF5: ...)".
template <typename T>
T Check(T result, const FileState& file, std::string_view object, std::string_view action) {
  if (result < 0) Fail(file, object, fmt::format("cannot {} ({})", action, Hdf5Detail()));
  return result;
}

/// For calls that fail only if flexmbs misuses HDF5 (building types and property lists).
template <typename T>
T CheckInternal(T result, std::string_view action) {
  if (result < 0) throw InternalError(fmt::format("HDF5: cannot {} ({})", action, Hdf5Detail()));
  return result;
}

/// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      close_ = other.close_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { Reset(); }

  hid_t get() const { return id_; }
  hid_t release() { return std::exchange(id_, H5I_INVALID_HID); }

 private:
  void Reset() noexcept {
    if (id_ >= 0) close_(id_);
    id_ = H5I_INVALID_HID;
  }
  hid_t id_;
  Closer close_;
};

// ------------------------------------------------------------------------------------------
// File state (defined in h5_file.cc)

/// The state of an open file; InternalError if it was committed or closed.
const FileState& Live(const std::shared_ptr<FileState>& file);

/// The state of an open file created for writing; InternalError otherwise.
FileState& Writable(const std::shared_ptr<FileState>& file);

// ------------------------------------------------------------------------------------------
// Names and units of objects in groups (defined in h5_group.cc)

/// The object path of the child `name` of `group_path` ("/refmod" + "M" -> "/refmod/M").
std::string Join(const std::string& group_path, std::string_view name);

/// InternalError unless `name` is one path component.
void CheckName(std::string_view name);

/// InternalError if `units` is empty.
void CheckUnits(std::string_view units, const std::string& object);

// ------------------------------------------------------------------------------------------
// Datasets (defined in h5_group.cc)

/// H5I_GROUP, H5I_DATASET, ... for the child `name` of `loc`, or H5I_BADID if there is none.
H5I_type_t ChildType(const FileState& file, hid_t loc, const std::string& object, std::string_view name);

/// The names of the links of the group `id` (named `object`), sorted by name.
std::vector<std::string> LinkNames(const FileState& file, hid_t id, const std::string& object);

/// An open dataset with its element type and extent.
struct DatasetView {
  Handle dataset;
  Handle type;
  H5T_class_t type_class = H5T_NO_CLASS;
  int rank = 0;  // -1 for a null dataspace, 0 for a scalar
  std::vector<hsize_t> dims;
  std::size_t count = 0;
};

/// Opens the dataset `name` of `loc` and reads its type and extent (nothing of its data).
DatasetView InspectDataset(const FileState& file, hid_t loc, const std::string& object,
                           std::string_view name);

// ------------------------------------------------------------------------------------------
// Storage layout and checksums of datasets (defined in h5_layout.cc)

/// The creation list of a dataset of `dims` ({} for a scalar) with `element_bytes` per value:
/// no values: contiguous (nothing to check); a scalar: compact, i.e. inside the object header
/// and under its checksum; else chunked in blocks of whole rows of about 1 MiB with the
/// Fletcher32 checksum on every chunk.
Handle DatasetCreationList(const std::vector<hsize_t>& dims, std::size_t element_bytes);

/// The rows (index 0) per chunk DatasetCreationList gives a dataset of `dims`: 0 if it is not
/// chunked (a scalar, or no values).
hsize_t ChunkRows(const std::vector<hsize_t>& dims, std::size_t element_bytes);

/// Writes the values of the chunked dataset `id` (created with DatasetCreationList(dims,
/// element_bytes); `values` row-major, in the file's byte order) as whole chunks with their
/// Fletcher32 checksums (core/fletcher32.h) through H5Dwrite_chunk, past HDF5's filter pipeline,
/// which copies every chunk into a fresh allocation of its own (docs/h5.md, "Cost of the
/// checksums"). The file is the same: HDF5 checks the checksums when it reads.
void WriteChecksummedChunks(const FileState& file, hid_t id, const std::string& object,
                            const std::vector<hsize_t>& dims, std::span<const std::byte> values,
                            std::size_t element_bytes);

/// The creation list of a chunked dataset with chunk dims `chunk` and the Fletcher32 checksum.
Handle ChecksummedChunks(const std::vector<hsize_t>& chunk);

/// Throws InputError "<file>: <object>: ..." unless the dataset's values fit in the file (a
/// damaged extent would allocate without bound), its stored bytes can hold them all, and every
/// chunk is in the chunk index with its checksum applied (a damaged index would read missing
/// chunks as fill values).
void CheckStorage(const FileState& file, const DatasetView& view, const std::string& object,
                  std::size_t element_bytes);

/// Throws InputError naming `object` unless the dataset is stored as flexmbs writes it: no
/// values, compact, or chunked with the Fletcher32 checksum.
void RequireChecksum(const FileState& file, const DatasetView& view, const std::string& object);

// ------------------------------------------------------------------------------------------
// SHA-256 of a dataset's values, for files written in place (defined in h5_digest.cc)

/// Writes the attributes `xxh3_128` (hex digest) and `xxh3_128_rows` (the leading rows it covers)
/// of the dataset `id` named `object`. Files written in place use the HDF5 1.8 format, whose
/// chunk index has no checksum: a damaged chunk address could point at zeros, which pass
/// Fletcher32. The digest, in the checksummed object header, catches that.
void WriteValuesDigest(const FileState& file, hid_t id, const std::string& object, const std::string& hex,
                       std::int64_t rows);

/// Records the digest of every live appendable dataset of `file` (WriteValuesDigest); before a
/// flush or the close of a file written in place.
void RecordRowDigests(FileState& file);

/// Writes the values digest of `bytes` (all `rows` rows) if `file` is written in place.
void WriteValuesDigestIfInPlace(const FileState& file, hid_t id, const std::string& object, const void* bytes,
                                std::size_t size, std::int64_t rows);

/// Throws InputError naming `object` unless the values read (`bytes`, `row_bytes` per row, as
/// stored: row-major) match the dataset's `xxh3_128` attribute (XXH3-128), or in files written
/// before it its `sha256` attribute (SHA-256), if it has one.
void CheckValuesDigest(const FileState& file, const DatasetView& view, const std::string& object, const void* bytes,
                       std::size_t row_bytes);

// ------------------------------------------------------------------------------------------
// Element types (defined in h5_types.cc)

/// True for IEEE binary64 in either byte order: the only floating-point type readers accept.
bool IsBinary64(hid_t type);

/// True for 64-bit two's-complement signed integers in either byte order.
bool IsInt64(hid_t type);

/// "" for a fixed-length ASCII or UTF-8 string type, else why flexmbs does not read it
/// (variable-length strings live on HDF5's global heap, which a damaged file can make HDF5
/// read out of bounds).
std::string StringTypeProblem(hid_t type);

/// A fixed-length UTF-8 string type of `size` bytes (at least 1), padded with '\0'.
Handle Utf8StringType(std::size_t size);

// ------------------------------------------------------------------------------------------
// Strings and attributes (defined in h5_attributes.cc)

/// Calls H5Dread or H5Aread with the memory type and buffer it is given.
using StringReader = std::function<herr_t(hid_t memory_type, void* buffer)>;

/// Reads `count` fixed-length strings of `file_type` through `read`; InputError naming
/// `object` for another string type (StringTypeProblem).
std::vector<std::string> ReadStringData(const FileState& file, const std::string& object,
                                        hid_t file_type, std::size_t count, const StringReader& read);

/// The scalar binary64 attribute `name` of `object_id`; InputError naming `object` otherwise.
double ReadDoubleAttribute(const FileState& file, hid_t object_id, const std::string& object,
                           std::string_view name);

/// The scalar 64-bit integer attribute `name` of `object_id`; InputError naming `object` otherwise.
std::int64_t ReadIntegerAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                  std::string_view name);

/// The scalar string attribute `name` of `object_id`; InputError naming `object` if it is
/// missing or not one string.
std::string ReadStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                std::string_view name);

/// Writes (or replaces) the scalar UTF-8 string attribute `name` of `object_id`.
void WriteStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                          std::string_view name, std::string_view value);

}  // namespace flexmbs::h5::detail
