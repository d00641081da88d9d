#include "fem/assembly.h"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <vector>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

// Node-to-node adjacency in compressed form: the neighbours of node n (itself included) are
// neighbours[offsets[n] .. offsets[n+1]), sorted.
struct NodeGraph {
  std::vector<int> offsets;
  std::vector<int> neighbours;
};

NodeGraph BuildNodeGraph(const Mesh& mesh) {
  const auto num_nodes = static_cast<int>(mesh.num_nodes());
  // Node-to-element incidence (elements numbered over all blocks).
  std::vector<int> incidence_offsets(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (const ElementBlock& block : mesh.blocks) {
    for (int v : block.connectivity.reshaped()) ++incidence_offsets[static_cast<std::size_t>(v) + 1];
  }
  for (int n = 0; n < num_nodes; ++n) incidence_offsets[n + 1] += incidence_offsets[n];
  std::vector<const int*> incident(static_cast<std::size_t>(incidence_offsets.back()));
  std::vector<int> element_size(incident.size());
  {
    std::vector<int> fill(incidence_offsets.begin(), incidence_offsets.end() - 1);
    for (const ElementBlock& block : mesh.blocks) {
      const auto rows = static_cast<int>(block.connectivity.rows());
      for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
        const int* element = block.connectivity.col(e).data();
        for (int a = 0; a < rows; ++a) {
          const auto slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(element[a])]++);
          incident[slot] = element;
          element_size[slot] = rows;
        }
      }
    }
  }
  NodeGraph graph;
  graph.offsets.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  std::vector<int> marker(static_cast<std::size_t>(num_nodes), -1);
  std::vector<int> row;
  for (int n = 0; n < num_nodes; ++n) {
    row.clear();
    for (int k = incidence_offsets[n]; k < incidence_offsets[n + 1]; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      for (int a = 0; a < element_size[ks]; ++a) {
        const int m = incident[ks][a];
        if (marker[static_cast<std::size_t>(m)] != n) {
          marker[static_cast<std::size_t>(m)] = n;
          row.push_back(m);
        }
      }
    }
    std::sort(row.begin(), row.end());
    graph.neighbours.insert(graph.neighbours.end(), row.begin(), row.end());
    graph.offsets[static_cast<std::size_t>(n) + 1] = static_cast<int>(graph.neighbours.size());
  }
  return graph;
}

// An empty CSC matrix with the 3x3-block pattern of the node graph, values zero.
Eigen::SparseMatrix<double> PatternMatrix(const NodeGraph& graph, Eigen::Index num_nodes) {
  const Eigen::Index n = 3 * num_nodes;
  Eigen::SparseMatrix<double> A(n, n);
  const Eigen::Index nnz = 9 * static_cast<Eigen::Index>(graph.neighbours.size());
  A.resizeNonZeros(nnz);
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  outer[0] = 0;
  for (Eigen::Index node = 0; node < num_nodes; ++node) {
    const int begin = graph.offsets[static_cast<std::size_t>(node)];
    const int end = graph.offsets[static_cast<std::size_t>(node) + 1];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index col = 3 * node + c;
      int pos = outer[col];
      for (int k = begin; k < end; ++k) {
        const int m = graph.neighbours[static_cast<std::size_t>(k)];
        for (int r = 0; r < 3; ++r) inner[pos++] = 3 * m + r;
      }
      outer[col + 1] = pos;
    }
  }
  std::fill(A.valuePtr(), A.valuePtr() + nnz, 0.0);
  return A;
}

// Calls add(a, b, c, base) for every node pair (a, b) of an element and axis c, `base` the
// value index of entry (3 nodes[a], 3 nodes[b] + c) in a matrix with the node-graph pattern
// (entry (3 nodes[a] + r, 3 nodes[b] + c) is at base + r).
template <class Add>
void ForEachBlockColumn(const Eigen::SparseMatrix<double>& A, std::span<const int> nodes, Add add) {
  const auto n = static_cast<int>(nodes.size());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (int b = 0; b < n; ++b) {
    const int nb = nodes[static_cast<std::size_t>(b)];
    const int* first = inner + outer[3 * nb];
    const int* last = inner + outer[3 * nb + 1];
    for (int a = 0; a < n; ++a) {
      const auto k3 = static_cast<int>(std::lower_bound(first, last, 3 * nodes[static_cast<std::size_t>(a)]) - first);
      for (int c = 0; c < 3; ++c) add(a, b, c, outer[3 * nb + c] + k3);
    }
  }
}

// Adds element matrices into CSC matrices that share the node-graph pattern.
class CscScatter final : public ElementMatrixVisitor {
 public:
  CscScatter(Eigen::SparseMatrix<double>* K, Eigen::SparseMatrix<double>* M) : K_(K), M_(M) {}

  void Visit(std::span<const int> nodes, const Eigen::MatrixXd& K_e,
             const Eigen::MatrixXd& m_e) override {
    double* k_values = K_->valuePtr();
    double* m_values = M_->valuePtr();
    ForEachBlockColumn(*K_, nodes, [&](int a, int b, int c, int base) {
      for (int r = 0; r < 3; ++r) k_values[base + r] += K_e(3 * a + r, 3 * b + c);
      m_values[base + c] += m_e(a, b);
    });
  }

 private:
  Eigen::SparseMatrix<double>* K_;
  Eigen::SparseMatrix<double>* M_;
};

[[noreturn]] void ThrowBadJacobian(const Mesh& mesh, const ElementBlock& block, Eigen::Index e,
                                   double det) {
  std::vector<std::size_t> node_ids;
  for (int v : block.connectivity.col(e)) node_ids.push_back(mesh.node_ids[static_cast<std::size_t>(v)]);
  throw InputError(fmt::format(
      "region '{}': {} element {} with nodes [{}] has non-positive Jacobian determinant {:.3g}",
      block.region, Traits(block.type).name, block.element_ids[static_cast<std::size_t>(e)],
      fmt::join(node_ids, ", "), det));
}

}  // namespace

void VisitElementMatrices(const Mesh& mesh, MassMatrixKind mass_kind, Eigen::Index first,
                          Eigen::Index end, ElementMatrixVisitor& visitor) {
  Eigen::Index offset = 0;
  Eigen::MatrixXd K_e, m_e;
  Eigen::Matrix3Xd X;
  for (const ElementBlock& block : mesh.blocks) {
    const Eigen::Index begin_local = std::max<Eigen::Index>(first - offset, 0);
    const Eigen::Index end_local = std::min<Eigen::Index>(end - offset, block.num_elements());
    offset += block.num_elements();
    if (begin_local >= end_local) continue;
    ElementIntegrator integrator(block.type);
    X.resize(3, integrator.num_nodes());
    for (Eigen::Index e = begin_local; e < end_local; ++e) {
      const auto nodes = block.connectivity.col(e);
      for (int a = 0; a < integrator.num_nodes(); ++a) X.col(a) = mesh.nodes.col(nodes(a));
      const double det_k = integrator.Stiffness(X, block.material, &K_e);
      const double det_m =
          integrator.ScalarMass(X, block.material.density_kg_m3, mass_kind, &m_e);
      if (!(std::min(det_k, det_m) > 0.0)) ThrowBadJacobian(mesh, block, e, std::min(det_k, det_m));
      visitor.Visit(std::span<const int>(nodes.data(), static_cast<std::size_t>(nodes.size())),
                    K_e, m_e);
    }
  }
}

Eigen::SparseMatrix<double> SystemPattern(const Mesh& mesh) {
  return PatternMatrix(BuildNodeGraph(mesh), mesh.num_nodes());
}

void AddScalarElementMatrix(std::span<const int> nodes, const Eigen::MatrixXd& a_e,
                            Eigen::SparseMatrix<double>* A) {
  double* values = A->valuePtr();
  ForEachBlockColumn(*A, nodes, [&](int a, int b, int c, int base) { values[base + c] += a_e(a, b); });
}

SystemMatrices AssembleSystem(const Mesh& mesh, MassMatrixKind mass_kind) {
  SystemMatrices system{SystemPattern(mesh), {}};
  system.mass = system.stiffness;
  CscScatter scatter(&system.stiffness, &system.mass);
  VisitElementMatrices(mesh, mass_kind, 0, mesh.num_elements(), scatter);
  if (mass_kind == MassMatrixKind::kLumped) system.mass.prune(0.0);
  return system;
}

}  // namespace flexmbs::fem
