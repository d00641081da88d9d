#include "tests/integrity/file_damage.h"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <utility>

#include "core/error.h"

namespace flexmbs::testing {
namespace {

/// Adds the chunks (or the contiguous block) of the dataset `name` under `object` to `map`.
void AddDataRegions(hid_t object, const char* name, std::vector<FileRegion>& map) {
  const hid_t dataset = H5Dopen2(object, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(dataset);
  const hid_t list = H5Dget_create_plist(dataset);
  if (H5Pget_layout(list) == H5D_CHUNKED) {
    hsize_t chunks = 0;
    H5Dget_num_chunks(dataset, space, &chunks);
    for (hsize_t i = 0; i < chunks; ++i) {
      hsize_t offset[8] = {};
      unsigned mask = 0;
      haddr_t address = 0;
      hsize_t size = 0;
      H5Dget_chunk_info(dataset, space, i, offset, &mask, &address, &size);
      map.push_back({address, address + size, "data chunk"});
    }
  } else if (H5Pget_layout(list) == H5D_CONTIGUOUS && H5Dget_offset(dataset) != HADDR_UNDEF) {
    map.push_back({H5Dget_offset(dataset), H5Dget_offset(dataset) + H5Dget_storage_size(dataset), "contiguous data"});
  }
  H5Pclose(list);
  H5Sclose(space);
  H5Dclose(dataset);
}

herr_t AddObject(hid_t object, const char* name, const H5O_info_t* info, void* data) {
  auto& map = *static_cast<std::vector<FileRegion>*>(data);
  map.push_back({info->addr, info->addr + info->hdr.space.total, "object header"});
  if (info->type == H5O_TYPE_DATASET) AddDataRegions(object, name, map);
  return 0;
}

/// HDF5's signatures of the file structures that are neither superblock, object header nor
/// data, and what they are.
const std::map<std::string, std::string>& Signatures() {
  static const std::map<std::string, std::string> signatures{
      {"TREE", "a version-1 B-tree node (1.8 chunk index) and its unused entry slots"},
      {"HEAP", "a local heap"},
      {"SNOD", "a symbol table node"},
      {"OCHK", "an object header continuation"},
      {"FRHP", "a fractal heap header"},
      {"FHDB", "a fractal heap block and its free space"},
      {"FHIB", "a fractal heap indirect block"},
      {"BTHD", "a version-2 B-tree header"},
      {"BTIN", "a version-2 B-tree node"},
      {"BTLF", "a version-2 B-tree leaf and its unused records"},
      {"FAHD", "a fixed array header (1.10 chunk index)"},
      {"FADB", "a fixed array data block"},
      {"EAHD", "an extensible array header"},
  };
  return signatures;
}

/// Regions from each signature in `bytes` to the next signature or region start.
void AddSignatureRegions(const std::string& bytes, std::vector<FileRegion>& map) {
  std::vector<std::pair<std::uint64_t, std::string>> found;
  for (const auto& [signature, kind] : Signatures()) {
    for (std::size_t at = bytes.find(signature); at != std::string::npos; at = bytes.find(signature, at + 1)) {
      found.emplace_back(at, "after the signature of " + kind);
    }
  }
  std::vector<std::uint64_t> starts{bytes.size()};
  for (const FileRegion& region : map) starts.push_back(region.begin);
  for (const auto& [at, kind] : found) starts.push_back(at);
  std::sort(starts.begin(), starts.end());
  for (const auto& [at, kind] : found) map.push_back({at, *std::upper_bound(starts.begin(), starts.end(), at), kind});
}

}  // namespace

std::vector<FileRegion> MapFile(const std::filesystem::path& path) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  FLEXMBS_CHECK(file >= 0, "the intact file opens");
  H5F_info2_t info;
  H5Fget_info2(file, &info);
  std::vector<FileRegion> map{{0, info.super.super_size, "superblock"}};
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, &AddObject, &map, H5O_INFO_BASIC | H5O_INFO_HDR);
  H5Fclose(file);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  AddSignatureRegions(bytes, map);
  return map;
}

std::string RegionOf(const std::vector<FileRegion>& map, std::uint64_t position) {
  for (const FileRegion& region : map) {
    if (position >= region.begin && position < region.end) return region.kind;
  }
  return "no structure: free space or padding between structures";
}

std::string DamageTally::Summary(const std::string& title) const {
  std::string text = fmt::format("{}: {} damaged copies, {} refused with one line naming the file, {} harmless, "
                                 "{} failures\n",
                                 title, copies, refused, copies - refused - static_cast<int>(failures.size()),
                                 failures.size());
  for (const auto& [where, count] : harmless) text += fmt::format("  harmless: {:6} in {}\n", count, where);
  return text;
}

void ReadDamagedFile(const std::filesystem::path& damaged, const Damage& damage, const DigestReader& read,
                     const std::string& intact_digest, DamageTally& tally) {
  ++tally.copies;
  try {
    const std::string digest = read(damaged);
    if (digest == intact_digest) {
      ++tally.harmless[damage.where];
    } else {
      tally.failures.push_back(fmt::format("{} ({}): accepted with changed values", damage.what, damage.where));
    }
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.starts_with(damaged.string() + ": ") && message.find('\n') == std::string::npos) {
      ++tally.refused;
    } else {
      tally.failures.push_back(fmt::format("{}: message not one line naming the file: {}", damage.what, message));
    }
  } catch (const std::exception& e) {
    tally.failures.push_back(fmt::format("{}: not an input error: {}", damage.what, e.what()));
  }
}

void ReadDamagedCopy(const std::string& bytes, const std::filesystem::path& damaged, const Damage& damage,
                     const DigestReader& read, const std::string& intact_digest, DamageTally& tally) {
  std::ofstream(damaged, std::ios::binary | std::ios::trunc) << bytes;
  ReadDamagedFile(damaged, damage, read, intact_digest, tally);
}

}  // namespace flexmbs::testing
