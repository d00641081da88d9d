// core/h5_file.h: AppendableDataset and Group::CreateAppendable, which sizes its chunks.

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
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
using detail::CheckUnits;
using detail::ChecksummedChunks;
using detail::FailFile;
using detail::FileState;
using detail::Handle;
using detail::Hdf5Detail;
using detail::Join;
using detail::Writable;
using detail::WriteStringAttribute;

namespace {

// Chunks of appendable datasets hold about this many bytes (HDF5 suggests 10 KiB to 1 MiB)...
constexpr std::size_t kChunkBytes = 64 * 1024;
// ...but at most this many rows, so a chunk never grows huge for tiny rows.
constexpr hsize_t kMaxChunkRows = 4096;

}  // namespace

// ============================================================================================
// Group::CreateAppendable

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
  const Handle create_list = ChecksummedChunks(chunk);
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
    : file_(std::move(file)),
      id_(id),
      path_(std::move(path)),
      row_shape_(std::move(row_shape)),
      digest_(std::make_shared<detail::RowsDigest>()) {
  for (std::int64_t extent : row_shape_) row_size_ *= extent;
  digest_->id = id_;
  digest_->object = path_;
  file_->row_digests.push_back(digest_);
}

AppendableDataset::AppendableDataset(AppendableDataset&& other) noexcept
    : file_(std::move(other.file_)),
      id_(std::exchange(other.id_, -1)),
      path_(std::move(other.path_)),
      row_shape_(std::move(other.row_shape_)),
      row_size_(other.row_size_),
      rows_(other.rows_),
      digest_(std::move(other.digest_)) {}

AppendableDataset& AppendableDataset::operator=(AppendableDataset&& other) noexcept {
  if (this != &other) {
    Close();
    file_ = std::move(other.file_);
    id_ = std::exchange(other.id_, -1);
    path_ = std::move(other.path_);
    row_shape_ = std::move(other.row_shape_);
    row_size_ = other.row_size_;
    rows_ = other.rows_;
    digest_ = std::move(other.digest_);
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
  digest_->hash.Update(row.data(), row.size() * sizeof(double));
  ++rows_;
  digest_->rows = rows_;
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
  FileState& file = Writable(file_);
  detail::RecordRowDigests(file);
  if (H5Fflush(file.id, H5F_SCOPE_LOCAL) < 0) {
    FailFile(file, fmt::format("cannot flush the file ({})", Hdf5Detail()));
  }
}

}  // namespace flexmbs::h5
