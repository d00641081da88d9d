#pragma once

// Private to core/h5_file.cc, core/h5_group.cc and core/h5_appendable.cc: the state that File,
// Group and AppendableDataset of one file share, HDF5 handles, and the error and naming helpers
// the three use. Not included by core/h5_file.h, so no HDF5 header reaches flexmbs' users.

#include <fmt/format.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/h5_file.h"

static_assert(std::is_same_v<hid_t, std::int64_t>, "h5_file.h stores hid_t as std::int64_t");

namespace flexmbs::h5::detail {

/// What File, Group and AppendableDataset of one file share. Groups and datasets check `open`
/// before closing their ids: File closes with H5F_CLOSE_STRONG, which closes them all.
struct FileState {
  std::filesystem::path path;       // as given by the caller; named in every message
  std::filesystem::path disk_path;  // where HDF5 writes: the temporary (kAtomic) or `path`
  WriteMode mode = WriteMode::kAtomic;
  bool writable = false;
  bool open = false;
  hid_t id = H5I_INVALID_HID;

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
// Strings and attributes (defined in h5_attributes.cc)

/// A variable-length UTF-8 string type.
Handle Utf8StringType();

/// Calls H5Dread or H5Aread with the memory type and buffer it is given.
using StringReader = std::function<herr_t(hid_t memory_type, void* buffer)>;

/// Reads `count` strings of `file_type` (variable- or fixed-length) through `read`.
std::vector<std::string> ReadStringData(const FileState& file, const std::string& object,
                                        hid_t file_type, std::size_t count, const StringReader& read);

/// The scalar string attribute `name` of `object_id`; InputError naming `object` if it is
/// missing or not one string.
std::string ReadStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                std::string_view name);

/// Writes (or replaces) the scalar UTF-8 string attribute `name` of `object_id`.
void WriteStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                          std::string_view name, std::string_view value);

}  // namespace flexmbs::h5::detail
