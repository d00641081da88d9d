// core/h5_file.h: Group's structure and datasets, and the shared helpers of h5_detail.h for
// names and units (attributes are in h5_attributes.cc).

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/h5_detail.h"
#include "core/h5_file.h"

namespace flexmbs::h5 {

using detail::Check;
using detail::CheckInternal;
using detail::CheckName;
using detail::CheckStorage;
using detail::CheckUnits;
using detail::CheckValuesDigest;
using detail::ChildType;
using detail::ChunkRows;
using detail::DatasetCreationList;
using detail::DatasetView;
using detail::Fail;
using detail::FileState;
using detail::Handle;
using detail::InspectDataset;
using detail::IsBinary64;
using detail::IsInt64;
using detail::Join;
using detail::Live;
using detail::ReadStringAttribute;
using detail::ReadStringData;
using detail::StringTypeProblem;
using detail::Utf8StringType;
using detail::Writable;
using detail::WriteChecksummedChunks;
using detail::WriteValuesDigestIfInPlace;
using detail::WriteStringAttribute;

namespace {

// ------------------------------------------------------------------------------------------
// Datasets

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

}  // namespace

namespace detail {

H5I_type_t ChildType(const FileState& file, hid_t loc, const std::string& object, std::string_view name) {
  const std::string n(name);
  if (Check(H5Lexists(loc, n.c_str(), H5P_DEFAULT), file, object, "look up the object") <= 0) {
    return H5I_BADID;
  }
  const Handle child(Check(H5Oopen(loc, n.c_str(), H5P_DEFAULT), file, object, "open the object"),
                     H5Oclose);
  return H5Iget_type(child.get());
}

std::vector<std::string> LinkNames(const FileState& file, hid_t id, const std::string& object) {
  H5G_info_t info;
  Check(H5Gget_info(id, &info), file, object, "list the group");
  std::vector<std::string> names;
  names.reserve(info.nlinks);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = Check(H5Lget_name_by_idx(id, ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                                    nullptr, 0, H5P_DEFAULT),
                                 file, object, "list the group");
    std::vector<char> buffer(static_cast<std::size_t>(length) + 1, '\0');
    Check(H5Lget_name_by_idx(id, ".", H5_INDEX_NAME, H5_ITER_INC, i, buffer.data(),
                             buffer.size(), H5P_DEFAULT),
          file, object, "list the group");
    names.emplace_back(buffer.data(), static_cast<std::size_t>(length));
  }
  return names;
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

}  // namespace detail

namespace {

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

/// Throws "<file>: <object>: expected 8-byte IEEE doubles, found 4-byte floating-point values"
/// unless the dataset holds binary64 (`type_class` H5T_FLOAT) or signed 64-bit integers.
void ExpectElements(const DatasetView& view, const FileState& file, const std::string& object) {
  const hid_t type = view.type.get();
  const std::size_t size = H5Tget_size(type);
  if (view.type_class == H5T_FLOAT && !IsBinary64(type)) {
    Fail(file, object, fmt::format("expected 8-byte IEEE doubles, found {}-byte floating-point values", size));
  }
  if (view.type_class == H5T_INTEGER && !IsInt64(type)) {
    Fail(file, object, fmt::format("expected 8-byte signed integers, found {}-byte {} integers", size,
                                   H5Tget_sign(type) == H5T_SGN_2 ? "signed" : "unsigned"));
  }
}

/// Checks the element type and storage of a dataset whose rank and class Expect checked, before
/// anything is allocated for its values.
template <typename T>
void CheckReadable(const DatasetView& view, const FileState& file, const std::string& object) {
  ExpectElements(view, file, object);
  CheckStorage(file, view, object, sizeof(T));
}

/// Reads the view.count values (row-major) of a dataset CheckReadable checked into `values`,
/// and checks them against their digest if the file has one.
template <typename T>
void ReadChecked(const DatasetView& view, const FileState& file, const std::string& object, hid_t memory_type,
                 T* values) {
  if (view.count == 0) return;
  Check(H5Dread(view.dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values), file, object,
        "read the dataset");
  const std::size_t rows = view.rank > 0 ? static_cast<std::size_t>(view.dims[0]) : 1;
  CheckValuesDigest(file, view, object, values, view.count / rows * sizeof(T));
}

/// The values of a dataset whose rank and class Expect checked.
template <typename T>
std::vector<T> ReadData(const DatasetView& view, const FileState& file, const std::string& object,
                        hid_t memory_type) {
  CheckReadable<T>(view, file, object);
  std::vector<T> data(view.count);
  ReadChecked(view, file, object, memory_type, data.data());
  return data;
}

/// `m` transposed, a band of columns at a time, each band in cache: a transposing copy of the
/// whole wide matrix strides through all of it for every column of the result (bench_sid_file
/// --parts, Group::ReadMatrix of a 512k-DOF body's modes: 0.142 s CPU before, 0.109 s in bands).
Eigen::MatrixXd Transposed(const Eigen::MatrixXd& m) {
  constexpr Eigen::Index kBand = 256;
  Eigen::MatrixXd t(m.cols(), m.rows());
  for (Eigen::Index c = 0; c < m.cols(); c += kBand) {
    const Eigen::Index n = std::min(kBand, m.cols() - c);
    t.middleRows(c, n) = m.middleCols(c, n).transpose();
  }
  return t;
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
  const Handle create_list = DatasetCreationList(dims, H5Tget_size(file_type));
  const Handle dataset(Check(H5Dcreate2(loc, n.c_str(), file_type, space.get(), H5P_DEFAULT,
                                        create_list.get(), H5P_DEFAULT),
                             file, object, "create the dataset"),
                       H5Dclose);
  std::size_t count = 1;
  for (hsize_t d : dims) count *= static_cast<std::size_t>(d);
  const std::size_t element_bytes = H5Tget_size(file_type);
  if (ChunkRows(dims, element_bytes) > 0) {
    // The memory types are the file types on a little-endian machine: the bytes are the file's.
    static_assert(std::endian::native == std::endian::little, "chunks are written in the file's byte order");
    FLEXMBS_CHECK(H5Tget_size(memory_type) == element_bytes, fmt::format("{}: memory and file types differ", object));
    WriteChecksummedChunks(file, dataset.get(), object, dims,
                           std::span(static_cast<const std::byte*>(data), count * element_bytes), element_bytes);
  } else if (count > 0) {
    Check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, object,
          "write the dataset");
  }
  WriteStringAttribute(file, dataset.get(), object, "units", units);
  WriteValuesDigestIfInPlace(file, dataset.get(), object, data, count * H5Tget_size(memory_type),
                             dims.empty() ? 1 : static_cast<std::int64_t>(dims[0]));
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Shared with h5_appendable.cc (declared in h5_detail.h)

namespace detail {

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

}  // namespace detail

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
  return detail::LinkNames(Live(file_), id_, path_);
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
  std::size_t size = 1;
  for (const std::string& s : values) {
    FLEXMBS_CHECK(s.find('\0') == std::string::npos,
                  fmt::format("{}: strings cannot hold '\\0'", object));
    size = std::max(size, s.size());
  }
  // Fixed-length strings of the longest one's size, padded with '\0': no global heap.
  std::vector<char> packed(values.size() * size, '\0');
  for (std::size_t i = 0; i < values.size(); ++i) std::copy(values[i].begin(), values[i].end(), packed.begin() + static_cast<std::ptrdiff_t>(i * size));
  const Handle type = Utf8StringType(size);
  const std::vector<hsize_t> dims{static_cast<hsize_t>(values.size())};
  const Handle space(Check(H5Screate_simple(1, dims.data(), nullptr), file, object, "create the dataspace"),
                     H5Sclose);
  const Handle create_list = DatasetCreationList(dims, size);
  const std::string n(name);
  const Handle dataset(Check(H5Dcreate2(id_, n.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                        create_list.get(), H5P_DEFAULT),
                             file, object, "create the dataset"),
                       H5Dclose);
  if (!values.empty()) {
    Check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()),
          file, object, "write the dataset");
  }
  WriteValuesDigestIfInPlace(file, dataset.get(), object, packed.data(), packed.size(),
                             static_cast<std::int64_t>(values.size()));
}

// --- reading -------------------------------------------------------------------------------

Eigen::MatrixXd Group::ReadMatrix(std::string_view name) const {
  const FileState& file = Live(file_);
  CheckName(name);
  const std::string object = Join(path_, name);
  const DatasetView view = InspectDataset(file, id_, object, name);
  Expect(view, file, object, 2, H5T_FLOAT);
  CheckReadable<double>(view, file, object);
  // The file's rows are the columns of a column-major (cols x rows) matrix, read as they are.
  Eigen::MatrixXd stored(static_cast<Eigen::Index>(view.dims[1]), static_cast<Eigen::Index>(view.dims[0]));
  ReadChecked(view, file, object, H5T_NATIVE_DOUBLE, stored.data());
  return Transposed(stored);
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
  const std::string problem = StringTypeProblem(view.type.get());
  if (!problem.empty()) Fail(file, object, problem);
  const std::size_t size = H5Tget_size(view.type.get());
  CheckStorage(file, view, object, size);
  std::vector<std::string> values =
      ReadStringData(file, object, view.type.get(), view.count, [&](hid_t memory_type, void* buffer) {
        return H5Dread(view.dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
      });
  // The digest is over the stored bytes: the strings padded with '\0' to the type's size.
  std::vector<char> packed(values.size() * size, '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::copy(values[i].begin(), values[i].end(), packed.begin() + static_cast<std::ptrdiff_t>(i * size));
  }
  if (!values.empty()) CheckValuesDigest(file, view, object, packed.data(), size);
  return values;
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

// Group::CreateAppendable is with AppendableDataset, in h5_appendable.cc.

}  // namespace flexmbs::h5
