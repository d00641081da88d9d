#include "fem/mesh_scatter.h"

#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <petscsys.h>
#include <string>
#include <vector>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

void Check(int code, const char* call) {
  if (code != MPI_SUCCESS) throw InternalError(fmt::format("MPI call {} failed with error {}", call, code));
}
#define FLEXMBS_MPI(call) Check((call), #call)

// Appends plain values and arrays to a byte buffer.
class Writer {
 public:
  template <typename T>
  void Put(const T& value) {
    Append(&value, sizeof(T));
  }
  template <typename T>
  void PutArray(const T* data, std::size_t count) {
    Put<std::uint64_t>(count);
    Append(data, count * sizeof(T));
  }
  void PutString(const std::string& s) { PutArray(s.data(), s.size()); }
  std::vector<char>& bytes() { return bytes_; }

 private:
  void Append(const void* data, std::size_t size) {
    const auto* p = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<char> bytes_;
};

// Reads back what Writer wrote, in the same order.
class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    T value;
    Take(&value, sizeof(T));
    return value;
  }
  template <typename T>
  std::size_t GetArray(T* data, std::size_t capacity) {
    const auto count = static_cast<std::size_t>(Get<std::uint64_t>());
    FLEXMBS_CHECK(count == capacity, "mesh part message: array of unexpected length");
    Take(data, count * sizeof(T));
    return count;
  }
  template <typename T>
  std::vector<T> GetVector() {
    const auto count = static_cast<std::size_t>(Peek<std::uint64_t>());
    std::vector<T> out(count);
    GetArray(out.data(), count);
    return out;
  }
  std::string GetString() {
    const std::vector<char> chars = GetVector<char>();
    return std::string(chars.begin(), chars.end());
  }

 private:
  template <typename T>
  T Peek() {
    T value;
    FLEXMBS_CHECK(at_ + sizeof(T) <= bytes_.size(), "mesh part message: truncated");
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    return value;
  }
  void Take(void* data, std::size_t size) {
    FLEXMBS_CHECK(at_ + size <= bytes_.size(), "mesh part message: truncated");
    if (size > 0) std::memcpy(data, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

std::vector<char> Serialize(const MeshPart& part) {
  Writer w;
  w.Put<std::int64_t>(part.num_global_nodes);
  w.Put<std::int64_t>(part.owned_nodes.begin);
  w.Put<std::int64_t>(part.owned_nodes.end);
  w.Put<std::int64_t>(part.mesh.num_nodes());
  w.PutArray(part.mesh.nodes.data(), static_cast<std::size_t>(part.mesh.nodes.size()));
  w.PutArray(part.mesh.node_ids.data(), part.mesh.node_ids.size());
  w.PutArray(part.global_node.data(), part.global_node.size());
  w.Put<std::uint64_t>(part.mesh.blocks.size());
  for (const ElementBlock& block : part.mesh.blocks) {
    w.Put<int>(static_cast<int>(block.type));
    w.PutString(block.region);
    w.PutString(block.material.name);
    w.Put(block.material.youngs_modulus_pa);
    w.Put(block.material.poisson_ratio);
    w.Put(block.material.density_kg_m3);
    w.Put<std::int64_t>(block.connectivity.rows());
    w.Put<std::int64_t>(block.connectivity.cols());
    w.PutArray(block.connectivity.data(), static_cast<std::size_t>(block.connectivity.size()));
    w.PutArray(block.element_ids.data(), block.element_ids.size());
  }
  return std::move(w.bytes());
}

MeshPart Deserialize(const std::vector<char>& bytes) {
  Reader r(bytes);
  MeshPart part;
  part.num_global_nodes = r.Get<std::int64_t>();
  part.owned_nodes.begin = r.Get<std::int64_t>();
  part.owned_nodes.end = r.Get<std::int64_t>();
  const auto num_nodes = r.Get<std::int64_t>();
  part.mesh.nodes.resize(3, num_nodes);
  r.GetArray(part.mesh.nodes.data(), static_cast<std::size_t>(part.mesh.nodes.size()));
  part.mesh.node_ids = r.GetVector<std::size_t>();
  part.global_node = r.GetVector<int>();
  const auto num_blocks = r.Get<std::uint64_t>();
  for (std::uint64_t b = 0; b < num_blocks; ++b) {
    ElementBlock block;
    block.type = static_cast<ElementType>(r.Get<int>());
    block.region = r.GetString();
    block.material.name = r.GetString();
    block.material.youngs_modulus_pa = r.Get<double>();
    block.material.poisson_ratio = r.Get<double>();
    block.material.density_kg_m3 = r.Get<double>();
    const auto rows = r.Get<std::int64_t>();
    const auto cols = r.Get<std::int64_t>();
    block.connectivity.resize(rows, cols);
    r.GetArray(block.connectivity.data(), static_cast<std::size_t>(block.connectivity.size()));
    block.element_ids = r.GetVector<std::size_t>();
    part.mesh.blocks.push_back(std::move(block));
  }
  return part;
}

constexpr int kTag = 4711;

}  // namespace

MeshPart ScatterMeshParts(const Mesh& mesh, const MeshPartition& partition) {
  int rank = 0, size = 1;
  FLEXMBS_MPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  FLEXMBS_MPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  if (rank == 0) {
    FLEXMBS_CHECK(partition.parts == size, "the partition must have one part per rank");
    for (int r = 1; r < size; ++r) {
      const std::vector<char> bytes = Serialize(ExtractMeshPart(mesh, partition, r));
      const auto count = static_cast<std::uint64_t>(bytes.size());
      FLEXMBS_MPI(MPI_Send(&count, 1, MPI_UINT64_T, r, kTag, PETSC_COMM_WORLD));
      FLEXMBS_MPI(MPI_Send(bytes.data(), static_cast<int>(count), MPI_CHAR, r, kTag, PETSC_COMM_WORLD));
    }
    return ExtractMeshPart(mesh, partition, 0);
  }
  std::uint64_t count = 0;
  FLEXMBS_MPI(MPI_Recv(&count, 1, MPI_UINT64_T, 0, kTag, PETSC_COMM_WORLD, MPI_STATUS_IGNORE));
  std::vector<char> bytes(count);
  FLEXMBS_MPI(MPI_Recv(bytes.data(), static_cast<int>(count), MPI_CHAR, 0, kTag, PETSC_COMM_WORLD, MPI_STATUS_IGNORE));
  return Deserialize(bytes);
}

}  // namespace flexmbs::fem
