#pragma once

#include <optional>
#include <string_view>

namespace flexmbs::fem {

/// The solid element types flexmbs assembles. Node order is gmsh's for each type
/// (gmsh reference manual, "Node ordering").
enum class ElementType { kTet4, kTet10, kHex8, kHex20, kWedge6, kWedge15 };

/// Static facts about one element type.
struct ElementTraits {
  ElementType type;
  std::string_view name;  ///< short name used in reports: "tet10", "hex20", ...
  int gmsh_type;          ///< gmsh's MSH element type number
  int num_nodes;
  int order;  ///< polynomial order of the geometry and displacement interpolation
};

/// All supported element types, in enum order.
inline constexpr ElementTraits kElementTraits[] = {
    {ElementType::kTet4, "tet4", 4, 4, 1},     {ElementType::kTet10, "tet10", 11, 10, 2},
    {ElementType::kHex8, "hex8", 5, 8, 1},     {ElementType::kHex20, "hex20", 17, 20, 2},
    {ElementType::kWedge6, "wedge6", 6, 6, 1}, {ElementType::kWedge15, "wedge15", 18, 15, 2},
};

/// The traits of `type`.
constexpr const ElementTraits& Traits(ElementType type) {
  return kElementTraits[static_cast<int>(type)];
}

/// The element type with gmsh type number `gmsh_type`, or nothing if flexmbs does not support it.
std::optional<ElementType> FromGmshType(int gmsh_type);

/// A human-readable name for any gmsh element type number (supported or not), for messages.
std::string_view GmshTypeName(int gmsh_type);

}  // namespace flexmbs::fem
