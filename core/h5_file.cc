#include "core/h5_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <system_error>
#include <type_traits>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"

static_assert(std::is_same_v<hid_t, std::int64_t>, "h5_file.h stores hid_t as std::int64_t");

namespace flexmbs::h5 {

namespace detail {

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

}  // namespace detail

namespace {

using detail::FileState;

// Chunks of appendable datasets hold about this many bytes (HDF5 suggests 10 KiB to 1 MiB)...
constexpr std::size_t kChunkBytes = 64 * 1024;
// ...but at most this many rows, so a chunk never grows huge for tiny rows.
constexpr hsize_t kMaxChunkRows = 4096;

// ------------------------------------------------------------------------------------------
// HDF5 errors and handles

herr_t CollectMessage(unsigned /*n*/, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<std::vector<std::string>*>(data);
  if (error != nullptr && error->desc != nullptr && error->desc[0] != '\0') {
    std::string message(error->desc);
    std::replace(message.begin(), message.end(), '\n', ' ');
    messages->push_back(std::move(message));
  }
  return 0;
}

/// The messages of HDF5's error stack for the last failed call, innermost (most specific)
/// first; clears the stack.
std::vector<std::string> TakeErrorStack() {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, &CollectMessage, &messages);
  H5Eclear2(H5E_DEFAULT);
  return messages;
}

/// "HDF5: <innermost message>" for the last failed call, to put in parentheses.
std::string Hdf5Detail() {
  const std::vector<std::string> messages = TakeErrorStack();
  return messages.empty() ? std::string("HDF5 error") : "HDF5: " + messages.front();
}

[[noreturn]] void FailFile(const FileState& file, std::string_view problem) {
  throw InputError(fmt::format("{}: {}", file.name(), problem));
}

[[noreturn]] void Fail(const FileState& file, std::string_view object, std::string_view problem) {
  throw InputError(fmt::format("{}: {}: {}", file.name(), object, problem));
}

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

/// Turns off HDF5's printing of its error stack (failures become one-line InputErrors).
/// Repeated on every Create/Open because it is cheap and a library may have turned it on.
void InitLibrary() {
  if (H5open() < 0) throw InternalError("HDF5: the library failed to initialise");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

/// File access: H5F_CLOSE_STRONG, so closing the file closes its groups and datasets too and
/// Commit never leaves the file half-open behind a live Group. The library version bounds
/// stay at the default (earliest): superblock v0/v2 has no "open for writing" flag, so a file
/// whose writer was killed still opens (with "latest", HDF5 1.10 refuses it until h5clear).
Handle FileAccessList() {
  Handle fapl(CheckInternal(H5Pcreate(H5P_FILE_ACCESS), "create a file access list"), H5Pclose);
  CheckInternal(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "set the file close degree");
  return fapl;
}

Handle Utf8StringType() {
  Handle type(CheckInternal(H5Tcopy(H5T_C_S1), "copy the string type"), H5Tclose);
  CheckInternal(H5Tset_size(type.get(), H5T_VARIABLE), "make a variable-length string type");
  CheckInternal(H5Tset_cset(type.get(), H5T_CSET_UTF8), "make a UTF-8 string type");
  return type;
}

// ------------------------------------------------------------------------------------------
// Names, paths, state

std::string Join(const std::string& group_path, std::string_view name) {
  return group_path == "/" ? fmt::format("/{}", name) : fmt::format("{}/{}", group_path, name);
}

void CheckName(std::string_view name) {
  FLEXMBS_CHECK(!name.empty() && name != "." && name.find('/') == std::string_view::npos,
                fmt::format("HDF5 object names here are one path component, got '{}'", name));
}

void CheckUnits(std::string_view units, const std::string& object) {
  FLEXMBS_CHECK(!units.empty(),
                fmt::format("{}: every numeric dataset needs units (\"1\" if dimensionless)",
                            object));
}

const FileState& Live(const std::shared_ptr<FileState>& file) {
  FLEXMBS_CHECK(file && file->open, "HDF5 object used after its file was committed or closed");
  return *file;
}

FileState& Writable(const std::shared_ptr<FileState>& file) {
  FLEXMBS_CHECK(file && file->open, "HDF5 object used after its file was committed or closed");
  FLEXMBS_CHECK(file->writable,
                fmt::format("{}: opened for reading, cannot be written", file->name()));
  return *file;
}

/// H5I_GROUP, H5I_DATASET, ... for the child `name` of `loc`, or H5I_BADID if there is none.
H5I_type_t ChildType(const FileState& file, hid_t loc, const std::string& object,
                     std::string_view name) {
  const std::string n(name);
  if (Check(H5Lexists(loc, n.c_str(), H5P_DEFAULT), file, object, "look up the object") <= 0) {
    return H5I_BADID;
  }
  const Handle child(Check(H5Oopen(loc, n.c_str(), H5P_DEFAULT), file, object, "open the object"),
                     H5Oclose);
  return H5Iget_type(child.get());
}

// ------------------------------------------------------------------------------------------
// Attributes (on groups and datasets)

void WriteAttribute(const FileState& file, hid_t object_id, const std::string& object,
                    std::string_view name, hid_t file_type, hid_t memory_type, const void* data) {
  const std::string n(name);
  const std::string what = fmt::format("write attribute '{}'", name);
  if (Check(H5Aexists(object_id, n.c_str()), file, object, what) > 0) {
    Check(H5Adelete(object_id, n.c_str()), file, object, what);
  }
  const Handle space(CheckInternal(H5Screate(H5S_SCALAR), "create a scalar dataspace"), H5Sclose);
  const Handle attribute(Check(H5Acreate2(object_id, n.c_str(), file_type, space.get(),
                                          H5P_DEFAULT, H5P_DEFAULT),
                               file, object, what),
                         H5Aclose);
  Check(H5Awrite(attribute.get(), memory_type, data), file, object, what);
}

void WriteStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                          std::string_view name, std::string_view value) {
  FLEXMBS_CHECK(value.find('\0') == std::string_view::npos,
                fmt::format("{}: attribute '{}': strings cannot hold '\\0'", object, name));
  const Handle type = Utf8StringType();
  const std::string text(value);
  const char* pointer = text.c_str();
  WriteAttribute(file, object_id, object, name, type.get(), type.get(), &pointer);
}

/// Reads `count` strings of `file_type` (variable- or fixed-length) through `read`, which
/// calls H5Dread or H5Aread with the memory type and buffer it is given.
template <typename ReadFunction>
std::vector<std::string> ReadStringData(const FileState& file, const std::string& object,
                                        hid_t file_type, std::size_t count, ReadFunction read) {
  std::vector<std::string> out;
  if (count == 0) return out;
  out.reserve(count);
  const H5T_cset_t cset = H5Tget_cset(file_type);
  if (Check(H5Tis_variable_str(file_type), file, object, "inspect the string type") > 0) {
    Handle memory_type(CheckInternal(H5Tcopy(H5T_C_S1), "copy the string type"), H5Tclose);
    CheckInternal(H5Tset_size(memory_type.get(), H5T_VARIABLE), "make a string type");
    CheckInternal(H5Tset_cset(memory_type.get(), cset), "set the character set");
    std::vector<char*> buffer(count, nullptr);
    Check(read(memory_type.get(), static_cast<void*>(buffer.data())), file, object,
          "read the strings");
    for (char* s : buffer) {
      out.emplace_back(s != nullptr ? s : "");
      if (s != nullptr) H5free_memory(s);
    }
  } else {
    const std::size_t size = H5Tget_size(file_type);
    if (size == 0) Fail(file, object, "cannot read the strings (size 0)");
    Handle memory_type(CheckInternal(H5Tcopy(H5T_C_S1), "copy the string type"), H5Tclose);
    CheckInternal(H5Tset_size(memory_type.get(), size), "make a string type");
    CheckInternal(H5Tset_cset(memory_type.get(), cset), "set the character set");
    CheckInternal(H5Tset_strpad(memory_type.get(), H5T_STR_NULLPAD), "set the string padding");
    std::vector<char> buffer(count * size, '\0');
    Check(read(memory_type.get(), static_cast<void*>(buffer.data())), file, object,
          "read the strings");
    for (std::size_t i = 0; i < count; ++i) {
      const char* begin = buffer.data() + i * size;
      out.emplace_back(begin, std::find(begin, begin + size, '\0'));
    }
  }
  return out;
}

std::string_view SingularKind(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_FLOAT: return "a double";
    case H5T_INTEGER: return "an integer";
    case H5T_STRING: return "a string";
    default: return "a value of another HDF5 type";
  }
}

/// Opens the attribute `name` of `object_id` and checks it holds one value of `expected`.
Handle OpenAttribute(const FileState& file, hid_t object_id, const std::string& object,
                     std::string_view name, H5T_class_t expected, Handle* type_out) {
  const std::string n(name);
  const std::string what = fmt::format("read attribute '{}'", name);
  if (Check(H5Aexists(object_id, n.c_str()), file, object, what) <= 0) {
    Fail(file, object, fmt::format("no attribute '{}'", name));
  }
  Handle attribute(Check(H5Aopen(object_id, n.c_str(), H5P_DEFAULT), file, object, what),
                   H5Aclose);
  Handle type(Check(H5Aget_type(attribute.get()), file, object, what), H5Tclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  const Handle space(Check(H5Aget_space(attribute.get()), file, object, what), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (type_class != expected) {
    Fail(file, object, fmt::format("attribute '{}': expected {}, found {}", name,
                                   SingularKind(expected), SingularKind(type_class)));
  }
  if (count != 1) {
    Fail(file, object,
         fmt::format("attribute '{}': expected one value, found {}", name, std::max<hssize_t>(count, 0)));
  }
  *type_out = std::move(type);
  return attribute;
}

std::string ReadStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                std::string_view name) {
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, object_id, object, name, H5T_STRING, &type);
  return ReadStringData(file, object, type.get(), 1, [&](hid_t memory_type, void* buffer) {
    return H5Aread(attribute.get(), memory_type, buffer);
  }).front();
}

// ------------------------------------------------------------------------------------------
// Datasets

/// An open dataset with its element class and extent.
struct DatasetView {
  Handle dataset;
  Handle type;
  H5T_class_t type_class = H5T_NO_CLASS;
  int rank = 0;  // -1 for a null dataspace, 0 for a scalar
  std::vector<hsize_t> dims;
  std::size_t count = 0;
};

Handle OpenDataset(const FileState& file, hid_t loc, const std::string& object,
                   std::string_view name) {
  switch (ChildType(file, loc, object, name)) {
    case H5I_BADID: Fail(file, object, "no such dataset");
    case H5I_DATASET: break;
    case H5I_GROUP: Fail(file, object, "is a group, expected a dataset");
    default: Fail(file, object, "is not a dataset");
  }
  const std::string n(name);
  return Handle(Check(H5Dopen2(loc, n.c_str(), H5P_DEFAULT), file, object, "open the dataset"),
                H5Dclose);
}

DatasetView InspectDataset(const FileState& file, hid_t loc, const std::string& object,
                           std::string_view name) {
  DatasetView view{OpenDataset(file, loc, object, name), Handle(H5I_INVALID_HID, H5Tclose),
                   H5T_NO_CLASS, 0, {}, 0};
  const hid_t ds = view.dataset.get();
  view.type = Handle(Check(H5Dget_type(ds), file, object, "read the dataset type"), H5Tclose);
  view.type_class = H5Tget_class(view.type.get());
  const Handle space(Check(H5Dget_space(ds), file, object, "read the dataset extent"), H5Sclose);
  const H5S_class_t space_class = H5Sget_simple_extent_type(space.get());
  if (space_class == H5S_NULL) {
    view.rank = -1;
    return view;
  }
  const int rank = Check(H5Sget_simple_extent_ndims(space.get()), file, object,
                         "read the dataset extent");
  view.rank = rank;
  view.dims.assign(static_cast<std::size_t>(rank), 0);
  if (rank > 0) {
    Check(H5Sget_simple_extent_dims(space.get(), view.dims.data(), nullptr), file, object,
          "read the dataset extent");
  }
  view.count = static_cast<std::size_t>(
      Check(H5Sget_simple_extent_npoints(space.get()), file, object, "read the dataset extent"));
  return view;
}

std::string_view PluralKind(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_FLOAT: return "doubles";
    case H5T_INTEGER: return "integers";
    case H5T_STRING: return "strings";
    default: return "values of another HDF5 type";
  }
}

std::string RankName(int rank) {
  if (rank < 0) return "null";
  if (rank == 0) return "scalar";
  return fmt::format("{}-D", rank);
}

/// Throws "<file>: <object>: expected a 1-D dataset of doubles, found 2-D" unless `view` has
/// `rank` and `type_class`.
void Expect(const DatasetView& view, const FileState& file, const std::string& object, int rank,
            H5T_class_t type_class) {
  if (view.rank == rank && view.type_class == type_class) return;
  std::string found;
  if (view.type_class != type_class) {
    found = fmt::format("a {} dataset of {}", RankName(view.rank), PluralKind(view.type_class));
  } else if (view.rank > 0) {
    found = RankName(view.rank);
  } else {
    found = fmt::format("a {} dataset", RankName(view.rank));
  }
  Fail(file, object, fmt::format("expected a {} dataset of {}, found {}", RankName(rank),
                                 PluralKind(type_class), found));
}

template <typename T>
std::vector<T> ReadData(const DatasetView& view, const FileState& file, const std::string& object,
                        hid_t memory_type) {
  std::vector<T> data(view.count);
  if (!data.empty()) {
    Check(H5Dread(view.dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          file, object, "read the dataset");
  }
  return data;
}

/// Creates the dataset `name` with `dims` ({} for a scalar), writes `data` (row-major) and
/// its "units" attribute.
void WriteNumeric(FileState& file, hid_t loc, const std::string& object, std::string_view name,
                  const std::vector<hsize_t>& dims, hid_t file_type, hid_t memory_type,
                  const void* data, std::string_view units) {
  CheckUnits(units, object);
  const Handle space(
      dims.empty()
          ? CheckInternal(H5Screate(H5S_SCALAR), "create a scalar dataspace")
          : Check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), file,
                  object, "create the dataspace"),
      H5Sclose);
  const std::string n(name);
  const Handle dataset(Check(H5Dcreate2(loc, n.c_str(), file_type, space.get(), H5P_DEFAULT,
                                        H5P_DEFAULT, H5P_DEFAULT),
                             file, object, "create the dataset"),
                       H5Dclose);
  std::size_t count = 1;
  for (hsize_t d : dims) count *= static_cast<std::size_t>(d);
  if (count > 0) {
    Check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, object,
          "write the dataset");
  }
  WriteStringAttribute(file, dataset.get(), object, "units", units);
}

/// fsync of a closed file, so a rename after it never exposes an empty file after a crash.
void SyncToDisk(const FileState& file, const std::filesystem::path& disk_path) {
  const int fd = ::open(disk_path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::error_code ec(errno, std::generic_category());
    if (fd >= 0) ::close(fd);
    FailFile(file, fmt::format("writing the file failed: {}", ec.message()));
  }
  ::close(fd);
}

/// Closes the file if open; a created kAtomic file that was not committed is removed.
void Abandon(FileState* state) noexcept {
  if (state == nullptr || !state->open) return;
  H5Fclose(state->id);
  H5Eclear2(H5E_DEFAULT);
  state->open = false;
  if (state->writable && state->mode == WriteMode::kAtomic) {
    std::error_code ec;
    std::filesystem::remove(state->disk_path, ec);
  }
}

}  // namespace

// ============================================================================================
// File

File::File(std::shared_ptr<detail::FileState> state) : state_(std::move(state)) {}

File::File(File&& other) noexcept = default;

File& File::operator=(File&& other) noexcept {
  if (this != &other) {
    Abandon(state_.get());
    state_ = std::move(other.state_);
  }
  return *this;
}

File::~File() { Abandon(state_.get()); }

File File::Create(const std::filesystem::path& path, WriteMode mode) {
  InitLibrary();
  auto state = std::make_shared<FileState>();
  state->path = path;
  state->mode = mode;
  state->writable = true;
  state->disk_path = mode == WriteMode::kAtomic ? TemporaryPathFor(path) : path;

  const std::filesystem::path folder = path.parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
    FailFile(*state, fmt::format("cannot create the file: no folder '{}'", folder.string()));
  }
  const Handle fapl = FileAccessList();
  const hid_t id = H5Fcreate(state->disk_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0) {
    const std::string detail = Hdf5Detail();
    if (mode == WriteMode::kAtomic) std::filesystem::remove(state->disk_path, ec);
    FailFile(*state, fmt::format("cannot create the file ({})", detail));
  }
  state->id = id;
  state->open = true;
  return File(std::move(state));
}

File File::Open(const std::filesystem::path& path) {
  InitLibrary();
  auto state = std::make_shared<FileState>();
  state->path = path;
  state->disk_path = path;

  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) FailFile(*state, "no such file");
  if (std::filesystem::is_directory(status)) FailFile(*state, "is a folder, not an HDF5 file");
  // H5Fis_hdf5 looks for the signature only: a truncated file still has one.
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 == 0) FailFile(*state, "not an HDF5 file");
  if (is_hdf5 < 0) FailFile(*state, fmt::format("cannot read the file ({})", Hdf5Detail()));

  const Handle fapl = FileAccessList();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (id < 0) {
    const std::vector<std::string> stack = TakeErrorStack();
    const std::string detail = stack.empty() ? "HDF5 error" : "HDF5: " + stack.front();
    const bool locked = std::any_of(stack.begin(), stack.end(), [](const std::string& m) {
      return m.find("unable to lock file") != std::string::npos;
    });
    if (locked) {
      // HDF5 reads HDF5_USE_FILE_LOCKING once, when the library starts: it must be set in
      // the reader's environment, not by setenv in a running process.
      FailFile(*state,
               "cannot open: another process is writing it (start the reader with "
               "HDF5_USE_FILE_LOCKING=FALSE to read its last flushed state)");
    }
    FailFile(*state, fmt::format("truncated or corrupt HDF5 file ({})", detail));
  }
  state->id = id;
  state->open = true;
  return File(std::move(state));
}

Group File::root() const {
  const FileState& file = Live(state_);
  const hid_t id = Check(H5Gopen2(file.id, "/", H5P_DEFAULT), file, "/", "open the group");
  return Group(state_, id, "/");
}

void File::Flush() {
  FileState& file = Writable(state_);
  if (H5Fflush(file.id, H5F_SCOPE_LOCAL) < 0) {
    FailFile(file, fmt::format("cannot flush the file ({})", Hdf5Detail()));
  }
}

void File::Commit() {
  FileState& file = Writable(state_);
  const herr_t closed = H5Fclose(file.id);
  file.open = false;
  try {
    if (closed < 0) FailFile(file, fmt::format("writing the file failed ({})", Hdf5Detail()));
    SyncToDisk(file, file.disk_path);
  } catch (...) {
    std::error_code ec;
    if (file.mode == WriteMode::kAtomic) std::filesystem::remove(file.disk_path, ec);
    throw;
  }
  if (file.mode == WriteMode::kAtomic) CommitTemporaryFile(file.disk_path, file.path);
}

const std::filesystem::path& File::path() const {
  FLEXMBS_CHECK(state_ != nullptr, "h5::File used after a move");
  return state_->path;
}

// ============================================================================================
// Group

Group::Group(std::shared_ptr<detail::FileState> file, std::int64_t id, std::string path)
    : file_(std::move(file)), id_(id), path_(std::move(path)) {}

Group::Group(Group&& other) noexcept
    : file_(std::move(other.file_)),
      id_(std::exchange(other.id_, -1)),
      path_(std::move(other.path_)) {}

Group& Group::operator=(Group&& other) noexcept {
  if (this != &other) {
    Close();
    file_ = std::move(other.file_);
    id_ = std::exchange(other.id_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

Group::~Group() { Close(); }

void Group::Close() noexcept {
  // After the file closed (H5F_CLOSE_STRONG) the id is already gone.
  if (file_ && file_->open && id_ >= 0) H5Gclose(id_);
  id_ = -1;
}

Group Group::CreateGroup(std::string_view name) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  const std::string n(name);
  const hid_t id = Check(H5Gcreate2(id_, n.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), file,
                         object, "create the group");
  return Group(file_, id, object);
}

Group Group::OpenGroup(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  switch (ChildType(file, id_, object, name)) {
    case H5I_BADID: Fail(file, object, "no such group");
    case H5I_GROUP: break;
    case H5I_DATASET: Fail(file, object, "is a dataset, expected a group");
    default: Fail(file, object, "is not a group");
  }
  const std::string n(name);
  const hid_t id = Check(H5Gopen2(id_, n.c_str(), H5P_DEFAULT), file, object, "open the group");
  return Group(file_, id, object);
}

bool Group::Has(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string n(name);
  return Check(H5Lexists(id_, n.c_str(), H5P_DEFAULT), file, Join(path_, name),
               "look up the object") > 0;
}

bool Group::HasGroup(std::string_view name) const {
  CheckName(name);
  return ChildType(Live(file_), id_, Join(path_, name), name) == H5I_GROUP;
}

bool Group::HasDataset(std::string_view name) const {
  CheckName(name);
  return ChildType(Live(file_), id_, Join(path_, name), name) == H5I_DATASET;
}

std::vector<std::string> Group::ChildNames() const {
  const FileState& file = Live(file_);
  H5G_info_t info;
  Check(H5Gget_info(id_, &info), file, path_, "list the group");
  std::vector<std::string> names;
  names.reserve(info.nlinks);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = Check(H5Lget_name_by_idx(id_, ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                                    nullptr, 0, H5P_DEFAULT),
                                 file, path_, "list the group");
    std::vector<char> buffer(static_cast<std::size_t>(length) + 1, '\0');
    Check(H5Lget_name_by_idx(id_, ".", H5_INDEX_NAME, H5_ITER_INC, i, buffer.data(),
                             buffer.size(), H5P_DEFAULT),
          file, path_, "list the group");
    names.emplace_back(buffer.data(), static_cast<std::size_t>(length));
  }
  return names;
}

std::vector<std::int64_t> Group::Shape(std::string_view name) const {
  CheckName(name);
  const DatasetView view = InspectDataset(Live(file_), id_, Join(path_, name), name);
  return std::vector<std::int64_t>(view.dims.begin(), view.dims.end());
}

// --- writing -------------------------------------------------------------------------------

void Group::WriteMatrix(std::string_view name, const Eigen::Ref<const Eigen::MatrixXd>& value,
                        std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = value;
  WriteNumeric(file, id_, object, name,
               {static_cast<hsize_t>(value.rows()), static_cast<hsize_t>(value.cols())},
               H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, row_major.data(), units);
}

void Group::WriteVector(std::string_view name, const Eigen::Ref<const Eigen::VectorXd>& value,
                        std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  WriteNumeric(file, id_, object, name, {static_cast<hsize_t>(value.size())}, H5T_IEEE_F64LE,
               H5T_NATIVE_DOUBLE, value.data(), units);
}

void Group::WriteScalar(std::string_view name, double value, std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  WriteNumeric(file, id_, object, name, {}, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, units);
}

void Group::WriteIntegers(std::string_view name, std::span<const std::int64_t> values,
                          std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  WriteNumeric(file, id_, object, name, {static_cast<hsize_t>(values.size())}, H5T_STD_I64LE,
               H5T_NATIVE_INT64, values.data(), units);
}

void Group::WriteIntegerMatrix(std::string_view name, const Eigen::Ref<const IntegerMatrix>& value,
                               std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  const Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major =
      value;
  WriteNumeric(file, id_, object, name,
               {static_cast<hsize_t>(value.rows()), static_cast<hsize_t>(value.cols())},
               H5T_STD_I64LE, H5T_NATIVE_INT64, row_major.data(), units);
}

void Group::WriteStrings(std::string_view name, const std::vector<std::string>& values) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& s : values) {
    FLEXMBS_CHECK(s.find('\0') == std::string::npos,
                  fmt::format("{}: strings cannot hold '\\0'", object));
    pointers.push_back(s.c_str());
  }
  const Handle type = Utf8StringType();
  const hsize_t dims[1] = {static_cast<hsize_t>(values.size())};
  const Handle space(Check(H5Screate_simple(1, dims, nullptr), file, object, "create the dataspace"),
                     H5Sclose);
  const std::string n(name);
  const Handle dataset(Check(H5Dcreate2(id_, n.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                        H5P_DEFAULT, H5P_DEFAULT),
                             file, object, "create the dataset"),
                       H5Dclose);
  if (!pointers.empty()) {
    Check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()),
          file, object, "write the dataset");
  }
}

// --- reading -------------------------------------------------------------------------------

Eigen::MatrixXd Group::ReadMatrix(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 2, H5T_FLOAT);
  const std::vector<double> data = ReadData<double>(view, file, object, H5T_NATIVE_DOUBLE);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      data.data(), static_cast<Eigen::Index>(view.dims[0]), static_cast<Eigen::Index>(view.dims[1]));
}

Eigen::VectorXd Group::ReadVector(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 1, H5T_FLOAT);
  const std::vector<double> data = ReadData<double>(view, file, object, H5T_NATIVE_DOUBLE);
  return Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
}

double Group::ReadScalar(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 0, H5T_FLOAT);
  return ReadData<double>(view, file, object, H5T_NATIVE_DOUBLE).front();
}

std::vector<std::int64_t> Group::ReadIntegers(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 1, H5T_INTEGER);
  return ReadData<std::int64_t>(view, file, object, H5T_NATIVE_INT64);
}

IntegerMatrix Group::ReadIntegerMatrix(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 2, H5T_INTEGER);
  const std::vector<std::int64_t> data = ReadData<std::int64_t>(view, file, object, H5T_NATIVE_INT64);
  return Eigen::Map<
      const Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      data.data(), static_cast<Eigen::Index>(view.dims[0]), static_cast<Eigen::Index>(view.dims[1]));
}

std::vector<std::string> Group::ReadStrings(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 1, H5T_STRING);
  return ReadStringData(file, object, view.type.get(), view.count,
                        [&](hid_t memory_type, void* buffer) {
                          return H5Dread(view.dataset.get(), memory_type, H5S_ALL, H5S_ALL,
                                         H5P_DEFAULT, buffer);
                        });
}

std::string Group::ReadUnits(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const Handle dataset = OpenDataset(file, id_, object, name);
  return ReadStringAttribute(file, dataset.get(), object, "units");
}

void Group::RequireUnits(std::string_view name, std::string_view expected) const {
  const std::string units = ReadUnits(name);
  if (units != expected) {
    Fail(*file_, Join(path_, name), fmt::format("units '{}', expected '{}'", units, expected));
  }
}

// --- attributes ----------------------------------------------------------------------------

void Group::SetStringAttribute(std::string_view name, std::string_view value) {
  WriteStringAttribute(Writable(file_), id_, path_, name, value);
}

void Group::SetDoubleAttribute(std::string_view name, double value) {
  WriteAttribute(Writable(file_), id_, path_, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Group::SetIntegerAttribute(std::string_view name, std::int64_t value) {
  WriteAttribute(Writable(file_), id_, path_, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

bool Group::HasAttribute(std::string_view name) const {
  const FileState& file = Live(file_);
  const std::string n(name);
  return Check(H5Aexists(id_, n.c_str()), file, path_, "look up the attribute") > 0;
}

std::string Group::GetStringAttribute(std::string_view name) const {
  return ReadStringAttribute(Live(file_), id_, path_, name);
}

double Group::GetDoubleAttribute(std::string_view name) const {
  const FileState& file = Live(file_);
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, id_, path_, name, H5T_FLOAT, &type);
  double value = 0.0;
  Check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), file, path_,
        fmt::format("read attribute '{}'", name));
  return value;
}

std::int64_t Group::GetIntegerAttribute(std::string_view name) const {
  const FileState& file = Live(file_);
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, id_, path_, name, H5T_INTEGER, &type);
  std::int64_t value = 0;
  Check(H5Aread(attribute.get(), H5T_NATIVE_INT64, &value), file, path_,
        fmt::format("read attribute '{}'", name));
  return value;
}

// --- appendable datasets -------------------------------------------------------------------

AppendableDataset Group::CreateAppendable(std::string_view name,
                                          std::vector<std::int64_t> row_shape,
                                          std::string_view units) {
  FileState& file = Writable(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  CheckUnits(units, object);
  FLEXMBS_CHECK(!Has(name), fmt::format("{}: {} already exists", file.name(), object));
  std::size_t row_size = 1;
  for (std::int64_t extent : row_shape) {
    FLEXMBS_CHECK(extent > 0, fmt::format("{}: row shape entries must be > 0", object));
    row_size *= static_cast<std::size_t>(extent);
  }
  // HDF5 limits a chunk to 4 GiB.
  FLEXMBS_CHECK(row_size * sizeof(double) < (std::size_t{1} << 32),
                fmt::format("{}: a row of {} doubles exceeds HDF5's chunk limit", object, row_size));
  const hsize_t chunk_rows =
      std::clamp<hsize_t>(kChunkBytes / (row_size * sizeof(double)), 1, kMaxChunkRows);

  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{chunk_rows};
  for (std::int64_t extent : row_shape) {
    dims.push_back(static_cast<hsize_t>(extent));
    max_dims.push_back(static_cast<hsize_t>(extent));
    chunk.push_back(static_cast<hsize_t>(extent));
  }
  const int rank = static_cast<int>(dims.size());
  const Handle space(Check(H5Screate_simple(rank, dims.data(), max_dims.data()), file, object,
                           "create the dataspace"),
                     H5Sclose);
  const Handle create_list(CheckInternal(H5Pcreate(H5P_DATASET_CREATE), "create a property list"),
                           H5Pclose);
  Check(H5Pset_chunk(create_list.get(), rank, chunk.data()), file, object, "set the chunk shape");
  const std::string n(name);
  Handle dataset(Check(H5Dcreate2(id_, n.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                  create_list.get(), H5P_DEFAULT),
                       file, object, "create the dataset"),
                 H5Dclose);
  WriteStringAttribute(file, dataset.get(), object, "units", units);
  return AppendableDataset(file_, dataset.release(), object, std::move(row_shape));
}

// ============================================================================================
// AppendableDataset

AppendableDataset::AppendableDataset(std::shared_ptr<detail::FileState> file, std::int64_t id,
                                     std::string path, std::vector<std::int64_t> row_shape)
    : file_(std::move(file)), id_(id), path_(std::move(path)), row_shape_(std::move(row_shape)) {
  for (std::int64_t extent : row_shape_) row_size_ *= extent;
}

AppendableDataset::AppendableDataset(AppendableDataset&& other) noexcept
    : file_(std::move(other.file_)),
      id_(std::exchange(other.id_, -1)),
      path_(std::move(other.path_)),
      row_shape_(std::move(other.row_shape_)),
      row_size_(other.row_size_),
      rows_(other.rows_) {}

AppendableDataset& AppendableDataset::operator=(AppendableDataset&& other) noexcept {
  if (this != &other) {
    Close();
    file_ = std::move(other.file_);
    id_ = std::exchange(other.id_, -1);
    path_ = std::move(other.path_);
    row_shape_ = std::move(other.row_shape_);
    row_size_ = other.row_size_;
    rows_ = other.rows_;
  }
  return *this;
}

AppendableDataset::~AppendableDataset() { Close(); }

void AppendableDataset::Close() noexcept {
  if (file_ && file_->open && id_ >= 0) H5Dclose(id_);
  id_ = -1;
}

void AppendableDataset::AppendRow(std::span<const double> row) {
  const FileState& file = Writable(file_);
  FLEXMBS_CHECK(id_ >= 0, "AppendableDataset used after a move");
  FLEXMBS_CHECK(static_cast<std::int64_t>(row.size()) == row_size_,
                fmt::format("{}: a row has {} values, got {}", path_, row_size_, row.size()));
  std::vector<hsize_t> dims{static_cast<hsize_t>(rows_ + 1)}, start{static_cast<hsize_t>(rows_)},
      count{1};
  for (std::int64_t extent : row_shape_) {
    dims.push_back(static_cast<hsize_t>(extent));
    start.push_back(0);
    count.push_back(static_cast<hsize_t>(extent));
  }
  Check(H5Dset_extent(id_, dims.data()), file, path_, "extend the dataset");
  const Handle file_space(Check(H5Dget_space(id_), file, path_, "extend the dataset"), H5Sclose);
  Check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                            nullptr),
        file, path_, "select the new row");
  const hsize_t row_size = static_cast<hsize_t>(row_size_);
  const Handle memory_space(CheckInternal(H5Screate_simple(1, &row_size, nullptr),
                                          "create the row dataspace"),
                            H5Sclose);
  Check(H5Dwrite(id_, H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                 row.data()),
        file, path_, "write the row");
  ++rows_;
}

void AppendableDataset::AppendRow(const Eigen::Ref<const Eigen::VectorXd>& row) {
  FLEXMBS_CHECK(row_shape_.size() == 1,
                fmt::format("{}: a vector row needs a row shape {{n}}", path_));
  AppendRow(std::span<const double>(row.data(), static_cast<std::size_t>(row.size())));
}

void AppendableDataset::AppendRow(double value) {
  FLEXMBS_CHECK(row_shape_.empty(), fmt::format("{}: a scalar row needs a row shape {{}}", path_));
  AppendRow(std::span<const double>(&value, 1));
}

void AppendableDataset::Flush() {
  const FileState& file = Writable(file_);
  if (H5Fflush(file.id, H5F_SCOPE_LOCAL) < 0) {
    FailFile(file, fmt::format("cannot flush the file ({})", Hdf5Detail()));
  }
}

}  // namespace flexmbs::h5
