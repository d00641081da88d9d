#pragma once

// The free DOFs of a model whose listed nodes are clamped, shared by the bench programs.

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace flexmbs::bench {

/// For each of `num_dofs` DOFs (3 node + axis), its index among the free DOFs, or -1 if its
/// node is listed in `fixed_nodes_file` (whitespace-separated 0-based node indices; empty
/// name: every DOF free). `num_free` receives the number of free DOFs. Throws
/// std::runtime_error for an unreadable file or a node out of range.
inline std::vector<long> FreeDofIndex(long num_dofs, const std::string& fixed_nodes_file, long* num_free) {
  std::vector<char> fixed(static_cast<std::size_t>(num_dofs), 0);
  if (!fixed_nodes_file.empty()) {
    std::ifstream in(fixed_nodes_file);
    if (!in) throw std::runtime_error("cannot open " + fixed_nodes_file);
    long node = 0;
    while (in >> node) {
      if (node < 0 || 3 * node + 2 >= num_dofs) {
        throw std::runtime_error("node index out of range in " + fixed_nodes_file);
      }
      for (long k = 0; k < 3; ++k) fixed[static_cast<std::size_t>(3 * node + k)] = 1;
    }
  }
  std::vector<long> index(static_cast<std::size_t>(num_dofs), -1);
  *num_free = 0;
  for (long i = 0; i < num_dofs; ++i) {
    if (!fixed[static_cast<std::size_t>(i)]) index[static_cast<std::size_t>(i)] = (*num_free)++;
  }
  return index;
}

}  // namespace flexmbs::bench
