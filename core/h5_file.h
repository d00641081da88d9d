#pragma once

// A small wrapper over the HDF5 C library for flexmbs' own files (`.sid.h5` bodies, results).
// No HDF5 header appears here: the library is linked PRIVATE to flexmbs_core.
//
// On-disk conventions (docs/h5.md):
// - a matrix is a 2-D dataset of IEEE binary64, row-major, dims (rows, cols): h5py/numpy see
//   the natural shape; a vector is 1-D, a scalar is a scalar dataspace;
// - integers are 64-bit signed; strings are 1-D datasets of fixed-length UTF-8;
// - every dataset with values is chunked with the Fletcher32 checksum (scalars: compact, under
//   the object header's checksum); readers accept binary64, int64 and fixed-length strings only;
// - every numeric dataset has a string attribute "units" ("1" if dimensionless);
// - File::Create writes a temporary beside the target and renames it into place on Commit.
//
// Errors: bad or unexpected file content, and I/O failures, throw flexmbs::InputError with one
// line naming the file and the object path ("body.sid.h5: /refmod/frequency_hz: expected a 1-D
// dataset of doubles, found 2-D"). Misuse by the caller (writing a name twice, writing to a file
// opened for reading, empty units, using a group after its file closed) throws InternalError.
// Not thread-safe: Debian's HDF5 is built without thread safety; use one thread per process.

#include <Eigen/Core>
#include <concepts>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace flexmbs::h5 {

namespace detail {
struct FileState;
struct RowsDigest;
}  // namespace detail

/// A matrix of 64-bit integers (face vertex indices, node ids) as stored on disk.
using IntegerMatrix = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic>;

/// How File::Create places the file.
enum class WriteMode {
  /// Write "<path>.tmp.<pid>" and rename it onto `path` on Commit: `path` holds either its
  /// previous content or the complete new file, never a partial one. For `.sid.h5` bodies.
  kAtomic,
  /// Write `path` directly (truncating it). Every Flush leaves a file that opens and reads
  /// back everything written before the Flush, even if the process is killed afterwards.
  /// For results written step by step.
  kInPlace,
};

class Group;
class AppendableDataset;

/// What Group::VerifyAll read.
struct VerifyReport {
  int groups = 0;
  int datasets = 0;
  int attributes = 0;
  std::int64_t values = 0;     ///< numbers and strings read, attributes included
  std::string content_sha256;  ///< SHA-256 over every name, attribute and value read, in name order
};

/// An open HDF5 file. Move-only; closing happens in Commit (writers) or the destructor.
class File {
 public:
  /// Creates a file for writing (see WriteMode). Throws InputError naming `path` if it cannot
  /// be created. In kAtomic mode, a File destroyed without Commit removes its temporary.
  static File Create(const std::filesystem::path& path, WriteMode mode = WriteMode::kAtomic);
  /// Opens an existing file for reading. Throws a one-line InputError naming `path` for a
  /// missing file ("no such file"), a file that is not HDF5 ("not an HDF5 file"), or a
  /// truncated or corrupt one ("truncated or corrupt HDF5 file (HDF5: ...)").
  static File Open(const std::filesystem::path& path);

  File(File&& other) noexcept;
  File& operator=(File&& other) noexcept;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  /// Closes the file. A created kAtomic file that was not committed is removed; a kInPlace
  /// one is kept with whatever was written (flushed or not).
  ~File();

  /// The root group "/".
  Group root() const;
  /// Writes everything buffered so far to disk (metadata included), so that the file on disk
  /// is complete up to this point. Precondition: created, not yet committed.
  void Flush();
  /// Finishes a created file: closes it (and every Group and AppendableDataset of it, which
  /// become unusable), syncs it, and in kAtomic mode renames it onto path(). Throws InputError
  /// naming path() if writing failed. Precondition: created, not yet committed.
  void Commit();

  /// The file's path as given to Create/Open (the final path, never the temporary).
  const std::filesystem::path& path() const;

 private:
  explicit File(std::shared_ptr<detail::FileState> state);
  std::shared_ptr<detail::FileState> state_;
};

/// A group of an open file: child groups, datasets and attributes, addressed by single-component
/// names (no '/'). Move-only; using a group after its file was committed or destroyed throws
/// InternalError. Const functions read, non-const ones write (files from Create only).
class Group {
 public:
  Group(Group&& other) noexcept;
  Group& operator=(Group&& other) noexcept;
  Group(const Group&) = delete;
  Group& operator=(const Group&) = delete;
  ~Group();

  /// The absolute object path ("/", "/refmod", "/nodes/tip").
  const std::string& path() const { return path_; }

  // --- structure ---------------------------------------------------------------------------
  /// Creates the child group `name` (which must not exist yet).
  Group CreateGroup(std::string_view name);
  /// The child group `name`; InputError "<file>: <path>/<name>: no such group" if missing.
  Group OpenGroup(std::string_view name) const;
  /// True if a child (group or dataset) named `name` exists.
  bool Has(std::string_view name) const;
  bool HasGroup(std::string_view name) const;
  bool HasDataset(std::string_view name) const;
  /// Names of all children, sorted by name.
  std::vector<std::string> ChildNames() const;
  /// Dimensions of the dataset `name`: {} for a scalar, {n} for a vector, {rows, cols}...
  std::vector<std::int64_t> Shape(std::string_view name) const;

  // --- writing datasets (each name once; `units` must not be empty, "1" if dimensionless) --
  /// A 2-D dataset of doubles, row-major, dims (rows, cols); zero rows or columns are kept.
  void WriteMatrix(std::string_view name, const Eigen::Ref<const Eigen::MatrixXd>& value,
                   std::string_view units);
  /// A 1-D dataset of doubles.
  void WriteVector(std::string_view name, const Eigen::Ref<const Eigen::VectorXd>& value,
                   std::string_view units);
  /// A scalar dataset (h5py shape ()) holding one double.
  void WriteScalar(std::string_view name, double value, std::string_view units);
  /// A 1-D dataset of 64-bit signed integers.
  void WriteIntegers(std::string_view name, std::span<const std::int64_t> values,
                     std::string_view units);
  /// The same from any range of integers (std::vector<int>, std::vector<Eigen::Index>, ...).
  template <std::ranges::input_range Range>
    requires std::integral<std::ranges::range_value_t<Range>>
  void WriteIntegers(std::string_view name, const Range& values, std::string_view units);
  /// A 2-D dataset of 64-bit signed integers, row-major, dims (rows, cols).
  void WriteIntegerMatrix(std::string_view name, const Eigen::Ref<const IntegerMatrix>& value,
                          std::string_view units);
  /// A 1-D dataset of fixed-length UTF-8 strings of the longest one's size, padded with '\0'
  /// (no units). Strings must not contain '\0'.
  void WriteStrings(std::string_view name, const std::vector<std::string>& values);

  // --- reading datasets: InputError naming file and object path on a missing dataset, a
  // different rank or a different element kind (doubles, integers, strings) ---------------
  Eigen::MatrixXd ReadMatrix(std::string_view name) const;
  Eigen::VectorXd ReadVector(std::string_view name) const;
  double ReadScalar(std::string_view name) const;
  std::vector<std::int64_t> ReadIntegers(std::string_view name) const;
  IntegerMatrix ReadIntegerMatrix(std::string_view name) const;
  /// Reads fixed-length string datasets; variable-length ones are refused (InputError).
  std::vector<std::string> ReadStrings(std::string_view name) const;
  /// The "units" attribute of the dataset `name`; InputError if it has none.
  std::string ReadUnits(std::string_view name) const;
  /// Throws InputError "<file>: <path>: units 'mm', expected 'm'" unless the units match.
  void RequireUnits(std::string_view name, std::string_view expected) const;

  // --- attributes of this group (setting an existing one replaces it) ----------------------
  void SetStringAttribute(std::string_view name, std::string_view value);
  void SetDoubleAttribute(std::string_view name, double value);
  void SetIntegerAttribute(std::string_view name, std::int64_t value);
  bool HasAttribute(std::string_view name) const;
  /// InputError naming file, group and attribute if missing or of another kind.
  std::string GetStringAttribute(std::string_view name) const;
  double GetDoubleAttribute(std::string_view name) const;
  std::int64_t GetIntegerAttribute(std::string_view name) const;

  // --- verification --------------------------------------------------------------------------
  /// Reads this group and everything under it in full: every attribute, and every dataset
  /// through the reader of its rank and type, after checking that it is stored as flexmbs
  /// writes it (no values, compact, or chunked with the Fletcher32 checksum, which HDF5 checks
  /// on the read). Throws the first problem as InputError naming the file and the object.
  VerifyReport VerifyAll() const;

  // --- incremental writing -----------------------------------------------------------------
  /// An extendible, chunked dataset of doubles with dims (0, row_shape...) that grows by one
  /// row per AppendRow: row_shape {} gives a 1-D series (N,), {n} gives (N, n), {3, k} gives
  /// (N, 3, k). Every entry of row_shape must be > 0.
  AppendableDataset CreateAppendable(std::string_view name, std::vector<std::int64_t> row_shape,
                                     std::string_view units);

 private:
  friend class File;
  Group(std::shared_ptr<detail::FileState> file, std::int64_t id, std::string path);
  void Close() noexcept;

  std::shared_ptr<detail::FileState> file_;
  std::int64_t id_ = -1;  // hid_t
  std::string path_;
};

/// A dataset that grows by rows, for results written while a simulation runs. Obtain from
/// Group::CreateAppendable. Rows written before a Flush survive a killed process when the
/// file was created in WriteMode::kInPlace; there every Flush and the Commit also record the
/// XXH3-128 of the rows so far (attributes `xxh3_128`, `xxh3_128_rows`; docs/h5.md). Move-only.
class AppendableDataset {
 public:
  AppendableDataset(AppendableDataset&& other) noexcept;
  AppendableDataset& operator=(AppendableDataset&& other) noexcept;
  AppendableDataset(const AppendableDataset&) = delete;
  AppendableDataset& operator=(const AppendableDataset&) = delete;
  ~AppendableDataset();

  /// Appends one row given flattened in row-major order; its size must be the product of the
  /// row shape (1 for scalar rows).
  void AppendRow(std::span<const double> row);
  /// Appends one row of a dataset with row shape {n}.
  void AppendRow(const Eigen::Ref<const Eigen::VectorXd>& row);
  /// Appends one value to a dataset with row shape {}.
  void AppendRow(double value);
  /// Flushes the whole file (HDF5 flushes per file), as File::Flush.
  void Flush();

  /// Rows written so far.
  std::int64_t rows() const { return rows_; }
  const std::string& path() const { return path_; }

 private:
  friend class Group;
  AppendableDataset(std::shared_ptr<detail::FileState> file, std::int64_t id, std::string path,
                    std::vector<std::int64_t> row_shape);
  void Close() noexcept;

  std::shared_ptr<detail::FileState> file_;
  std::int64_t id_ = -1;  // hid_t
  std::string path_;
  std::vector<std::int64_t> row_shape_;
  std::int64_t row_size_ = 1;
  std::int64_t rows_ = 0;
  std::shared_ptr<detail::RowsDigest> digest_;  // of the rows appended, shared with the file
};

template <std::ranges::input_range Range>
  requires std::integral<std::ranges::range_value_t<Range>>
void Group::WriteIntegers(std::string_view name, const Range& values, std::string_view units) {
  std::vector<std::int64_t> converted;
  for (const auto& v : values) {
    if constexpr (std::unsigned_integral<std::ranges::range_value_t<Range>>) {
      FLEXMBS_CHECK(static_cast<std::uint64_t>(v) <=
                        static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()),
                    "integer does not fit in 64-bit signed storage");
    }
    converted.push_back(static_cast<std::int64_t>(v));
  }
  WriteIntegers(name, std::span<const std::int64_t>(converted), units);
}

}  // namespace flexmbs::h5
