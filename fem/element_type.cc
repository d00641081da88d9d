#include "fem/element_type.h"

namespace flexmbs::fem {

std::optional<ElementType> FromGmshType(int gmsh_type) {
  for (const ElementTraits& t : kElementTraits) {
    if (t.gmsh_type == gmsh_type) return t.type;
  }
  return std::nullopt;
}

std::string_view GmshTypeName(int gmsh_type) {
  switch (gmsh_type) {
    case 1: return "line2";
    case 2: return "tri3";
    case 3: return "quad4";
    case 4: return "tet4";
    case 5: return "hex8";
    case 6: return "wedge6";
    case 7: return "pyramid5";
    case 8: return "line3";
    case 9: return "tri6";
    case 10: return "quad9";
    case 11: return "tet10";
    case 12: return "hex27";
    case 13: return "wedge18";
    case 14: return "pyramid14";
    case 15: return "point";
    case 16: return "quad8";
    case 17: return "hex20";
    case 18: return "wedge15";
    case 19: return "pyramid13";
    case 29: return "tet20";
    default: return "unknown";
  }
}

}  // namespace flexmbs::fem
