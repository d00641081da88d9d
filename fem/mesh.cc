#include "fem/mesh.h"

#include <span>

#include "core/sha256.h"

namespace flexmbs::fem {

Eigen::Index Mesh::num_elements() const {
  Eigen::Index n = 0;
  for (const ElementBlock& b : blocks) n += b.num_elements();
  return n;
}

std::string MeshSha256(const Mesh& mesh) {
  std::vector<std::byte> content;
  auto append = [&content](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::byte*>(data);
    content.insert(content.end(), bytes, bytes + size);
  };
  append(mesh.nodes.data(), static_cast<std::size_t>(mesh.nodes.size()) * sizeof(double));
  for (const ElementBlock& block : mesh.blocks) {
    const std::string_view type = Traits(block.type).name;
    append(type.data(), type.size());
    append(block.region.data(), block.region.size() + 1);
    append(block.connectivity.data(), static_cast<std::size_t>(block.connectivity.size()) * sizeof(int));
  }
  return Sha256Hex(content);
}

}  // namespace flexmbs::fem
