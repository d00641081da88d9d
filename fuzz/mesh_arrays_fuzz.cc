// Fuzz target: the mesh import's checks on what gmsh returns (fem::MeshFromGmshArrays,
// fem::MeshNodesOfTags) with element blocks and node arrays of any shape, no gmsh. Bad arrays
// must end in an InputError; a mesh that passes must be well formed (checked here).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "fem/gmsh_mesh_arrays.h"

namespace {

using flexmbs::fem::GmshElementBlock;
using flexmbs::fem::GmshNodes;
using flexmbs::fem::Mesh;

/// Aborts (a finding) with `what` unless `ok`.
void Require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "mesh_arrays_fuzz: %s\n", what);
  std::abort();
}

/// Reads the input front to back (the layout fuzz/make_mesh_arrays_seeds.py writes); zeros
/// once the bytes run out.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  /// The next byte.
  std::uint8_t Byte() { return at_ < size_ ? data_[at_++] : 0; }
  /// The next `sizeof(T)` bytes, little-endian, as a T.
  template <typename T>
  T Raw() {
    std::uint8_t bytes[sizeof(T)];
    for (std::uint8_t& b : bytes) b = Byte();
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

/// A node or element tag: a flag byte, then one byte (a small tag, below 128) or eight (any).
std::size_t Tag(ByteReader& in) {
  return in.Byte() < 128 ? in.Byte() % 128 : in.Raw<std::uint64_t>();
}

/// A coordinate: a flag byte, then a 16-bit integer in mm (below 128) or any double's 8 bytes.
double Coordinate(ByteReader& in) {
  return in.Byte() < 128 ? in.Raw<std::int16_t>() / 1000.0 : in.Raw<double>();
}

/// `count`, or (odd byte) `count` plus -2 .. 2, never below zero.
std::size_t AboutCount(ByteReader& in, std::size_t count) {
  const std::uint8_t b = in.Byte();
  if (b % 2 == 0) return count;
  const int delta = (b / 2) % 5 - 2;
  return delta < 0 && count < static_cast<std::size_t>(-delta) ? 0 : count + static_cast<std::size_t>(delta);
}

/// A block: gmsh type (byte), element count (byte, below 8), element tags, node tags (about the
/// count the type needs).
GmshElementBlock ReadBlock(ByteReader& in, std::size_t b) {
  GmshElementBlock block;
  block.gmsh_type = in.Byte() % 32;
  block.region = "region " + std::to_string(b);
  const std::size_t elements = in.Byte() % 8;
  for (std::size_t e = 0; e < elements; ++e) block.element_tags.push_back(Tag(in));
  const auto type = flexmbs::fem::FromGmshType(block.gmsh_type);
  const std::size_t per_element = type ? static_cast<std::size_t>(flexmbs::fem::Traits(*type).num_nodes) : 4;
  const std::size_t tags = AboutCount(in, elements * per_element);
  for (std::size_t k = 0; k < tags; ++k) block.node_tags.push_back(Tag(in));
  return block;
}

/// Nodes: count (byte, below 64), tags, then about three coordinates per node.
GmshNodes ReadNodes(ByteReader& in) {
  GmshNodes nodes;
  const std::size_t count = in.Byte() % 64;
  for (std::size_t i = 0; i < count; ++i) nodes.tags.push_back(Tag(in));
  const std::size_t coords = AboutCount(in, 3 * count);
  for (std::size_t k = 0; k < coords; ++k) nodes.coords.push_back(Coordinate(in));
  return nodes;
}

/// Aborts unless `mesh` is well formed: node tags sorted and unique, finite coordinates, every
/// connectivity entry a node, every node used, node sets sorted indices.
void CheckMesh(const Mesh& mesh, const std::vector<std::size_t>& set_tags) {
  Require(static_cast<std::size_t>(mesh.num_nodes()) == mesh.node_ids.size(), "node count");
  Require(std::adjacent_find(mesh.node_ids.begin(), mesh.node_ids.end(), std::greater_equal<>()) ==
              mesh.node_ids.end(),
          "node tags not sorted and unique");
  Require(mesh.nodes.allFinite(), "non-finite coordinate");
  std::vector<bool> used(mesh.node_ids.size(), false);
  for (const flexmbs::fem::ElementBlock& block : mesh.blocks) {
    Require(block.connectivity.rows() == flexmbs::fem::Traits(block.type).num_nodes, "connectivity rows");
    Require(static_cast<std::size_t>(block.num_elements()) == block.element_ids.size(), "element count");
    for (Eigen::Index k = 0; k < block.connectivity.size(); ++k) {
      const int node = block.connectivity.data()[k];
      Require(node >= 0 && node < mesh.num_nodes(), "connectivity out of range");
      used[static_cast<std::size_t>(node)] = true;
    }
  }
  Require(std::all_of(used.begin(), used.end(), [](bool u) { return u; }), "unused node");
  const std::vector<int> set = flexmbs::fem::MeshNodesOfTags(mesh, set_tags);
  Require(std::is_sorted(set.begin(), set.end()), "node set not sorted");
  for (int node : set) Require(node >= 0 && node < mesh.num_nodes(), "node set out of range");
}

}  // namespace

/// libFuzzer's entry point: block count (byte), blocks, nodes, then a node set's tags.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  std::vector<GmshElementBlock> blocks;
  const std::size_t num_blocks = in.Byte() % 4;
  for (std::size_t b = 0; b < num_blocks; ++b) blocks.push_back(ReadBlock(in, b));
  const GmshNodes nodes = ReadNodes(in);
  std::vector<std::size_t> set_tags;
  while (!in.empty()) set_tags.push_back(Tag(in));
  try {
    CheckMesh(flexmbs::fem::MeshFromGmshArrays("fuzz.msh", std::move(blocks), nodes), set_tags);
  } catch (const flexmbs::InputError&) {
  }
  return 0;
}
