// core/h5_file.h: File (create, open, flush, commit) and the shared helpers of h5_detail.h for
// HDF5 errors and file state.

#include "core/h5_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <system_error>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/h5_detail.h"

namespace flexmbs::h5 {

namespace detail {

// ------------------------------------------------------------------------------------------
// HDF5 errors

namespace {

herr_t CollectMessage(unsigned /*n*/, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<std::vector<std::string>*>(data);
  if (error != nullptr && error->desc != nullptr && error->desc[0] != '\0') {
    std::string message(error->desc);
    std::replace(message.begin(), message.end(), '\n', ' ');
    messages->push_back(std::move(message));
  }
  return 0;
}

}  // namespace

std::vector<std::string> TakeErrorStack() {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, &CollectMessage, &messages);
  H5Eclear2(H5E_DEFAULT);
  return messages;
}

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

// ------------------------------------------------------------------------------------------
// File state

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

}  // namespace detail

using detail::Check;
using detail::CheckInternal;
using detail::FailFile;
using detail::FileState;
using detail::Handle;
using detail::Hdf5Detail;
using detail::Live;
using detail::TakeErrorStack;
using detail::Writable;

namespace {

/// Turns off HDF5's printing of its error stack (failures become one-line InputErrors).
/// Repeated on every Create/Open because it is cheap and a library may have turned it on.
void InitLibrary() {
  if (H5open() < 0) throw InternalError("HDF5: the library failed to initialise");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

/// File access: H5F_CLOSE_STRONG, so closing the file closes its groups and datasets too and
/// Commit never leaves the file half-open behind a live Group.
Handle FileAccessList() {
  Handle fapl(CheckInternal(H5Pcreate(H5P_FILE_ACCESS), "create a file access list"), H5Pclose);
  CheckInternal(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "set the file close degree");
  return fapl;
}

/// The access list of a new file, with the file format versions of its mode (docs/h5.md): both
/// checksum their metadata (superblock, object headers with their attributes, group indexes).
/// kAtomic: the 1.10 format, whose chunk indexes are checksummed too; its "open for writing"
/// flag does not matter, as only a closed file is renamed into place. kInPlace: the 1.8 format
/// (superblock 2, no such flag), so that a file whose writer was killed still opens (with the
/// 1.10 format HDF5 refuses it until h5clear); its chunk indexes (version-1 B-trees) have no
/// checksum, and readers check that every chunk is there (CheckStorage).
Handle CreationAccessList(WriteMode mode) {
  Handle fapl = FileAccessList();
  const H5F_libver_t version = mode == WriteMode::kAtomic ? H5F_LIBVER_V110 : H5F_LIBVER_V18;
  CheckInternal(H5Pset_libver_bounds(fapl.get(), version, version), "set the file format version");
  return fapl;
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
  const Handle fapl = CreationAccessList(mode);
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
  detail::RecordRowDigests(file);
  if (H5Fflush(file.id, H5F_SCOPE_LOCAL) < 0) {
    FailFile(file, fmt::format("cannot flush the file ({})", Hdf5Detail()));
  }
}

void File::Commit() {
  FileState& file = Writable(state_);
  detail::RecordRowDigests(file);
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

}  // namespace flexmbs::h5
