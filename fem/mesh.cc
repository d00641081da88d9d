#include "fem/mesh.h"

namespace flexmbs::fem {

Eigen::Index Mesh::num_elements() const {
  Eigen::Index n = 0;
  for (const ElementBlock& b : blocks) n += b.num_elements();
  return n;
}

}  // namespace flexmbs::fem
