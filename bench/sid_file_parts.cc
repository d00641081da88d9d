#include "bench/sid_file_parts.h"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bench/cpu_and_wall_time.h"
#include "core/fletcher32.h"
#include "core/h5_file.h"
#include "core/sha256.h"
#include "core/xxh3.h"
#include "sid/sid_digest.h"

// HDF5's own Fletcher32, the function its filter calls (exported, not in its public headers).
extern "C" std::uint32_t H5_checksum_fletcher32(const void* data, std::size_t length);

namespace flexmbs::bench {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// How a dataset is stored: chunk_bytes 0 is contiguous.
struct Storage {
  std::string name;
  std::size_t chunk_bytes = 0;
  bool fletcher32 = false;
};

/// Writes `values` as the one dataset of a new file at `path` with `storage`, through H5Dwrite.
void WriteWith(const std::filesystem::path& path, const RowMajor& values, const Storage& storage) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {static_cast<hsize_t>(values.rows()), static_cast<hsize_t>(values.cols())};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t list = H5Pcreate(H5P_DATASET_CREATE);
  if (storage.chunk_bytes > 0) {
    const hsize_t rows = std::clamp<hsize_t>(storage.chunk_bytes / (dims[1] * sizeof(double)), 1, dims[0]);
    const hsize_t chunk[2] = {rows, dims[1]};
    H5Pset_chunk(list, 2, chunk);
    if (storage.fletcher32) H5Pset_fletcher32(list);
  }
  const hid_t dataset = H5Dcreate2(file, "phi", H5T_IEEE_F64LE, space, H5P_DEFAULT, list, H5P_DEFAULT);
  H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(dataset);
  H5Pclose(list);
  H5Sclose(space);
  H5Fclose(file);
}

/// Reads the dataset WriteWith wrote into `values` (of its size) through H5Dread.
void ReadInto(const std::filesystem::path& path, RowMajor& values) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, "phi", H5P_DEFAULT);
  H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(dataset);
  H5Fclose(file);
}

}  // namespace

void PrintChecksumParts(const sid::ReducedBody& body, const std::filesystem::path& dir, int repeat) {
  const RowMajor phi = body.phi;
  const std::span<const std::byte> bytes = std::as_bytes(std::span(phi.data(), static_cast<std::size_t>(phi.size())));
  const double mb = static_cast<double>(bytes.size()) / 1e6;
  fmt::print("  parts, CPU s (phi: {:.1f} MB)\n", mb);
  const auto line = [&](const std::string& what, double seconds) {
    fmt::print("    {:<46} {:>7.4f} s {:>6.2f} GB/s of phi\n", what, seconds, mb / 1e3 / seconds);
  };
  std::uint32_t sink = 0;
  line("content digest, SHA-256 (schema 4)",
       Fastest(repeat, [&] { sink += ContentDigest(body, sid::DigestAlgorithm::kSha256).size(); }).cpu);
  line("content digest, XXH3-128 (schema 5)",
       Fastest(repeat, [&] { sink += ContentDigest(body, sid::DigestAlgorithm::kXxh3_128).size(); }).cpu);
  line("SHA-256 over phi", Fastest(repeat, [&] { sink += Sha256Hex(bytes).size(); }).cpu);
  line("XXH3-128 over phi", Fastest(repeat, [&] { sink += Xxh3_128Hex(bytes).size(); }).cpu);
  // Whether the two sums should share a pass: each over all of phi in turn (phi read twice from
  // memory), against both over each 64 KiB block while it is in cache.
  line("Fletcher32, then XXH3-128, over phi", Fastest(repeat, [&] {
         sink += Fletcher32(bytes) + static_cast<std::uint32_t>(Xxh3_128Hex(bytes).size());
       }).cpu);
  line("both per 64 KiB block of phi, one pass", Fastest(repeat, [&] {
         Xxh3_128 hash;
         for (std::size_t start = 0; start < bytes.size(); start += std::size_t{1} << 16) {
           const std::span<const std::byte> block = bytes.subspan(start, std::min(bytes.size() - start, std::size_t{1} << 16));
           sink += Fletcher32(block);
           hash.Update(block.data(), block.size());
         }
         sink += static_cast<std::uint32_t>(hash.HexDigest().size());
       }).cpu);
  line("Fletcher32 over phi, flexmbs", Fastest(repeat, [&] { sink += Fletcher32(bytes); }).cpu);
  line("Fletcher32 over phi, HDF5's",
       Fastest(repeat, [&] { sink += H5_checksum_fletcher32(bytes.data(), bytes.size()); }).cpu);
  RowMajor back(phi.rows(), phi.cols());  // the raw runs' destination
  const std::vector<Storage> storages{{"contiguous", 0, false},          {"chunks of 1 MiB", 1 << 20, false},
                                      {"chunks of 64 KiB + Fletcher32", 1 << 16, true},
                                      {"chunks of 256 KiB + Fletcher32", 1 << 18, true},
                                      {"chunks of 1 MiB + Fletcher32", 1 << 20, true},
                                      {"chunks of 4 MiB + Fletcher32", 1 << 22, true},
                                      {"chunks of 16 MiB + Fletcher32", 1 << 24, true}};
  const std::filesystem::path path = dir / "bench_sid_file_parts.h5";
  for (const Storage& storage : storages) {
    line("phi through HDF5, write, " + storage.name, Fastest(repeat, [&] { WriteWith(path, phi, storage); }).cpu);
    back.setZero();
    line("phi through HDF5, read,  " + storage.name, Fastest(repeat, [&] { ReadInto(path, back); }).cpu);
    if (back != phi) fmt::print("    (read back differs!)\n");
  }
  h5::File read_back = [&] {
    h5::File file = h5::File::Create(path);
    file.root().WriteMatrix("phi", body.phi, "m/q");
    file.Commit();
    return h5::File::Open(path);
  }();
  line("phi to row-major (the copy inside WriteMatrix)", Fastest(repeat, [&] { back = body.phi; }).cpu);
  line("phi through flexmbs, Group::WriteMatrix", Fastest(repeat, [&] {
         h5::File file = h5::File::Create(path);
         file.root().WriteMatrix("phi", body.phi, "m/q");
         file.Commit();
       }).cpu);
  line("phi through flexmbs, Group::ReadMatrix", Fastest(repeat, [&] {
         sink += static_cast<std::uint32_t>(h5::File::Open(path).root().ReadMatrix("phi").size());
       }).cpu);
  std::filesystem::remove(path);
  if (sink == 1) fmt::print(" ");  // keeps the sums computed
}

}  // namespace flexmbs::bench
