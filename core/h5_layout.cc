// core/h5_detail.h: how datasets are stored (chunked with the Fletcher32 checksum, compact
// scalars), how whole datasets are written chunk by chunk, and the checks readers make of a
// dataset's storage before they read it.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <hdf5.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/fletcher32.h"
#include "core/h5_detail.h"

namespace flexmbs::h5::detail {

namespace {

/// Chunks of datasets written whole hold whole rows, about this many bytes (HDF5 suggests
/// 10 KiB to 1 MiB; its default chunk cache holds 1 MiB).
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
/// A chunk of a file being read may be at most this large: HDF5's own limit (chunks under 4 GiB).
constexpr hsize_t kMaxChunkBytes = hsize_t{1} << 32;
/// The Fletcher32 checksum stored after each chunk's values.
constexpr hsize_t kFletcher32Bytes = 4;

/// The bytes of one row (index 0) of a dataset of `dims` with `element_bytes` per value.
std::size_t RowBytes(const std::vector<hsize_t>& dims, std::size_t element_bytes) {
  std::size_t bytes = element_bytes;
  for (std::size_t d = 1; d < dims.size(); ++d) bytes *= static_cast<std::size_t>(dims[d]);
  return bytes;
}

/// Throws InputError naming `object` unless every chunk of the chunked dataset `view` is found
/// in its chunk index with its filters applied. The 1.8 format's chunk index (version-1 B-trees)
/// has no checksum: a damaged key would make HDF5 read its chunk as fill values, or skip the
/// chunk's checksum. Two queries, as they walk the index differently: H5Dget_chunk_storage_size
/// looks the chunk up as H5Dread does (through the keys that bound each child), and
/// H5Dget_chunk_info_by_coord visits every entry and gives its filter mask. The chunk shape is
/// checked first: every dimension at least 1 and at most a fixed maximum dimension, and every
/// chunk stored as its values and the 4-byte Fletcher32 checksum, the one filter the writer
/// sets (ChecksummedChunks). HDF5 1.10.8 trusts a damaged shape: a chunk wider than the
/// dataset's fixed second dimension made H5Dread copy past its buffers (fuzz_results_reader).
void CheckChunks(const FileState& file, const DatasetView& view, const std::string& object, hid_t create_list,
                 std::size_t element_bytes) {
  std::vector<hsize_t> chunk(view.dims.size(), 0), max_dims(view.dims.size(), 0);
  if (H5Pget_chunk(create_list, static_cast<int>(chunk.size()), chunk.data()) != static_cast<int>(chunk.size())) {
    H5Eclear2(H5E_DEFAULT);
    Fail(file, object, fmt::format("the chunk shape does not have the dataset's rank {}", chunk.size()));
  }
  const Handle space(Check(H5Dget_space(view.dataset.get()), file, object, "read the dataset extent"), H5Sclose);
  Check(H5Sget_simple_extent_dims(space.get(), nullptr, max_dims.data()), file, object, "read the dataset extent");
  hsize_t chunk_bytes = element_bytes;
  for (std::size_t d = 0; d < chunk.size(); ++d) {
    const bool fits = chunk[d] >= 1 && (max_dims[d] == H5S_UNLIMITED || chunk[d] <= max_dims[d]) &&
                      chunk[d] <= kMaxChunkBytes / chunk_bytes;
    if (!fits) {
      Fail(file, object, fmt::format("chunks of [{}] do not fit dims [{}] of {}-byte values", fmt::join(chunk, ", "),
                                     fmt::join(view.dims, ", "), element_bytes));
    }
    chunk_bytes *= chunk[d];
  }
  std::vector<hsize_t> offset(view.dims.size(), 0);
  for (;;) {
    unsigned mask = 0;
    haddr_t address = HADDR_UNDEF;
    hsize_t size = 0, stored = 0;
    if (H5Dget_chunk_storage_size(view.dataset.get(), offset.data(), &stored) < 0 || stored == 0 ||
        H5Dget_chunk_info_by_coord(view.dataset.get(), offset.data(), &mask, &address, &size) < 0 ||
        address == HADDR_UNDEF || mask != 0) {
      H5Eclear2(H5E_DEFAULT);
      Fail(file, object, fmt::format("the chunk at [{}] is missing from the chunk index or skips its checksum",
                                     fmt::join(offset, ", ")));
    }
    if (stored != chunk_bytes + kFletcher32Bytes || size != stored) {
      Fail(file, object, fmt::format("the chunk at [{}] holds {} bytes, not its {} bytes of values and checksum",
                                     fmt::join(offset, ", "), stored, chunk_bytes + kFletcher32Bytes));
    }
    std::size_t d = offset.size();
    while (d > 0) {
      --d;
      offset[d] += chunk[d];
      if (offset[d] < view.dims[d]) break;
      offset[d] = 0;
      if (d == 0) return;
    }
    if (offset.empty()) return;
  }
}

}  // namespace

Handle ChecksummedChunks(const std::vector<hsize_t>& chunk) {
  Handle list(CheckInternal(H5Pcreate(H5P_DATASET_CREATE), "create a dataset creation list"), H5Pclose);
  CheckInternal(H5Pset_chunk(list.get(), static_cast<int>(chunk.size()), chunk.data()), "set the chunk shape");
  CheckInternal(H5Pset_fletcher32(list.get()), "add the Fletcher32 checksum");
  return list;
}

hsize_t ChunkRows(const std::vector<hsize_t>& dims, std::size_t element_bytes) {
  if (dims.empty() || std::find(dims.begin(), dims.end(), hsize_t{0}) != dims.end()) return 0;
  return std::clamp<hsize_t>(kChunkBytes / (RowBytes(dims, element_bytes)), 1, dims[0]);
}

Handle DatasetCreationList(const std::vector<hsize_t>& dims, std::size_t element_bytes) {
  const hsize_t chunk_rows = ChunkRows(dims, element_bytes);
  if (chunk_rows == 0) {
    Handle list(CheckInternal(H5Pcreate(H5P_DATASET_CREATE), "create a dataset creation list"), H5Pclose);
    if (dims.empty()) CheckInternal(H5Pset_layout(list.get(), H5D_COMPACT), "make a compact dataset");
    return list;
  }
  std::vector<hsize_t> chunk = dims;
  chunk[0] = chunk_rows;
  return ChecksummedChunks(chunk);
}

void WriteChecksummedChunks(const FileState& file, hid_t id, const std::string& object,
                            const std::vector<hsize_t>& dims, std::span<const std::byte> values,
                            std::size_t element_bytes) {
  const hsize_t chunk_rows = ChunkRows(dims, element_bytes);
  const std::size_t row_bytes = RowBytes(dims, element_bytes);
  FLEXMBS_CHECK(chunk_rows > 0 && values.size() == dims[0] * row_bytes,
                fmt::format("{}: {} bytes of values for dims [{}]", object, values.size(), fmt::join(dims, ", ")));
  const std::size_t chunk_bytes = static_cast<std::size_t>(chunk_rows) * row_bytes;
  // One chunk at a time in a buffer that stays in cache: its values, the fill value 0 past the
  // last row (HDF5 stores edge chunks whole and checksums them so), the checksum after them.
  std::vector<std::byte> chunk(chunk_bytes + kFletcher32Bytes);
  std::vector<hsize_t> offset(dims.size(), 0);
  for (hsize_t row = 0; row < dims[0]; row += chunk_rows) {
    const std::size_t bytes = static_cast<std::size_t>(std::min(chunk_rows, dims[0] - row)) * row_bytes;
    const std::span<const std::byte> part = values.subspan(static_cast<std::size_t>(row) * row_bytes, bytes);
    std::copy(part.begin(), part.end(), chunk.begin());
    std::fill(chunk.begin() + static_cast<std::ptrdiff_t>(bytes), chunk.end(), std::byte{0});
    const std::uint32_t checksum = Fletcher32(std::span(chunk).first(chunk_bytes));
    for (std::size_t k = 0; k < kFletcher32Bytes; ++k) {
      chunk[chunk_bytes + k] = static_cast<std::byte>((checksum >> (8 * k)) & 0xff);  // little-endian, as HDF5
    }
    offset[0] = row;
    Check(H5Dwrite_chunk(id, H5P_DEFAULT, 0, offset.data(), chunk.size(), chunk.data()), file, object,
          "write the dataset");
  }
}

void CheckStorage(const FileState& file, const DatasetView& view, const std::string& object,
                  std::size_t element_bytes) {
  if (view.count == 0) return;
  hsize_t file_bytes = 0;
  Check(H5Fget_filesize(file.id, &file_bytes), file, object, "read the file size");
  if (view.count > std::numeric_limits<std::size_t>::max() / element_bytes ||
      view.count * element_bytes > file_bytes) {
    Fail(file, object, fmt::format("dims [{}] of {}-byte values do not fit in the file ({} bytes)",
                                   fmt::join(view.dims, ", "), element_bytes, file_bytes));
  }
  const std::size_t bytes = view.count * element_bytes;
  const hsize_t stored = H5Dget_storage_size(view.dataset.get());
  if (stored < bytes) {
    Fail(file, object, fmt::format("{} values of {} bytes, but only {} bytes stored: part of the data is missing",
                                   view.count, element_bytes, stored));
  }
  const Handle list(Check(H5Dget_create_plist(view.dataset.get()), file, object, "read the storage layout"),
                    H5Pclose);
  if (H5Pget_layout(list.get()) == H5D_CHUNKED) CheckChunks(file, view, object, list.get(), element_bytes);
}

void RequireChecksum(const FileState& file, const DatasetView& view, const std::string& object) {
  if (view.count == 0) return;
  const Handle list(Check(H5Dget_create_plist(view.dataset.get()), file, object, "read the storage layout"),
                    H5Pclose);
  const H5D_layout_t layout = H5Pget_layout(list.get());
  if (layout == H5D_COMPACT) return;
  if (layout == H5D_CHUNKED) {
    const int filters = Check(H5Pget_nfilters(list.get()), file, object, "read the filters");
    for (int i = 0; i < filters; ++i) {
      unsigned flags = 0, config = 0;
      std::size_t values = 0;
      if (H5Pget_filter2(list.get(), static_cast<unsigned>(i), &flags, &values, nullptr, 0, nullptr, &config) ==
          H5Z_FILTER_FLETCHER32) {
        return;
      }
    }
  }
  Fail(file, object, "the data has no checksum (not written by this flexmbs)");
}

}  // namespace flexmbs::h5::detail
