// Consistency of a ReducedBody: the sizes its modes and nodes require (the writer's precondition
// and the reader's last check).
#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "sid/sid_file.h"
#include "sid/sid_layout.h"

namespace flexmbs::sid {
namespace {

/// "" if `block` has m0 of rows x cols and consistent higher orders, else the problem.
std::string CheckTaylor(std::string_view name, const TaylorMatrix& block, Eigen::Index rows,
                        Eigen::Index cols, Eigen::Index num_modes) {
  if (block.m0.rows() != rows || block.m0.cols() != cols) {
    return fmt::format("{} is {} x {}, expected {} x {}", name, block.m0.rows(), block.m0.cols(), rows, cols);
  }
  if (!block.IsConsistent(num_modes)) {
    return fmt::format("{}: {} order-1 and {} order-2 blocks for {} modes (or a block of another shape)",
                       name, block.m1.size(), block.m2.size(), num_modes);
  }
  return {};
}

/// The expected shape of each invariant for n modes, in the order of layout::kInvariants.
std::array<std::pair<Eigen::Index, Eigen::Index>, 11> InvariantShapes(Eigen::Index n) {
  return {{{3, 1}, {3, 3}, {n, 3}, {n, 3}, {n, n}, {3, 3 * n}, {n, 3 * n}, {n, 6}, {n, n}, {n, n}, {n, 1}}};
}

std::string CheckNode(const Node& node, Eigen::Index n, Eigen::Index num_fe_nodes) {
  const std::string what = fmt::format("node '{}'", node.name);
  for (int k : node.fe_nodes) {
    if (k < 0 || k >= num_fe_nodes) return fmt::format("{}: FE node {} out of range", what, k);
  }
  const std::array<std::pair<Eigen::Index, Eigen::Index>, 4> shapes{{{3, 1}, {3, n}, {3, n}, {3, 3}}};
  for (std::size_t f = 0; f < layout::kNodeFields.size(); ++f) {
    const layout::NodeField& field = layout::kNodeFields[f];
    std::string problem = CheckTaylor(fmt::format("{} {}", what, field.name), node.*field.member,
                                      shapes[f].first, shapes[f].second, n);
    if (!problem.empty()) return problem;
  }
  return {};
}

std::string CheckSurface(const ContactSurface& surface, Eigen::Index n, Eigen::Index num_fe_nodes) {
  const std::string what = fmt::format("surface '{}'", surface.name);
  const auto num_vertices = surface.vertices.rows();
  if (static_cast<Eigen::Index>(surface.fe_nodes.size()) != num_vertices) {
    return fmt::format("{}: {} FE nodes for {} vertices", what, surface.fe_nodes.size(), num_vertices);
  }
  for (int k : surface.fe_nodes) {
    if (k < 0 || k >= num_fe_nodes) return fmt::format("{}: FE node {} out of range", what, k);
  }
  const int corners = std::accumulate(surface.face_sizes.begin(), surface.face_sizes.end(), 0);
  if (corners != static_cast<int>(surface.face_vertices.size())) {
    return fmt::format("{}: face sizes add up to {}, but {} face vertices", what, corners,
                       surface.face_vertices.size());
  }
  for (int v : surface.face_vertices) {
    if (v < 0 || v >= num_vertices) return fmt::format("{}: face vertex {} out of range", what, v);
  }
  if (surface.face_normals.rows() != static_cast<Eigen::Index>(surface.face_sizes.size())) {
    return fmt::format("{}: {} normals for {} faces", what, surface.face_normals.rows(), surface.face_sizes.size());
  }
  if (surface.phi.rows() != 3 * num_vertices || surface.phi.cols() != n) {
    return fmt::format("{}: phi is {} x {}, expected {} x {}", what, surface.phi.rows(), surface.phi.cols(),
                       3 * num_vertices, n);
  }
  return {};
}

std::string CheckVisualSurface(const VisualSurface& surface, Eigen::Index num_fe_nodes) {
  for (int size : surface.face_sizes) {
    if (size < 3) return fmt::format("visual surface: a polygon of {} nodes", size);
  }
  const int corners = std::accumulate(surface.face_sizes.begin(), surface.face_sizes.end(), 0);
  if (corners != static_cast<int>(surface.face_nodes.size())) {
    return fmt::format("visual surface: face sizes add up to {}, but {} face nodes", corners,
                       surface.face_nodes.size());
  }
  for (int k : surface.face_nodes) {
    if (k < 0 || k >= num_fe_nodes) return fmt::format("visual surface: FE node {} out of range", k);
  }
  return {};
}

}  // namespace

std::string FindInconsistency(const ReducedBody& body) {
  const Eigen::Index n = body.num_modes();
  const auto count = static_cast<std::size_t>(n);
  if (body.phi.rows() != 3 * body.node_positions.cols()) {
    return fmt::format("/modes/phi has {} rows for {} nodes", body.phi.rows(), body.node_positions.cols());
  }
  if (body.mode_names.size() != count || body.mode_kinds.size() != count ||
      static_cast<std::size_t>(body.frequency_hz.size()) != count ||
      static_cast<std::size_t>(body.relative_residuals.size()) != count) {
    return fmt::format("{} modes, but {} names, {} kinds, {} frequencies, {} residuals", n,
                       body.mode_names.size(), body.mode_kinds.size(), body.frequency_hz.size(),
                       body.relative_residuals.size());
  }
  const auto shapes = InvariantShapes(n);
  for (std::size_t f = 0; f < layout::kInvariants.size(); ++f) {
    const layout::InvariantField& field = layout::kInvariants[f];
    std::string problem = CheckTaylor(field.name, body.*field.member, shapes[f].first, shapes[f].second, n);
    if (!problem.empty()) return problem;
  }
  if (!body.stiffening.empty()) {
    auto square = [n](const Eigen::MatrixXd& K) { return K.rows() == n && K.cols() == n; };
    const GeometricStiffening& s = body.stiffening;
    if (!std::all_of(s.K0t.begin(), s.K0t.end(), square) || !std::all_of(s.K0r.begin(), s.K0r.end(), square) ||
        !std::all_of(s.K0omega.begin(), s.K0omega.end(), square)) {
      return fmt::format("a stiffening matrix is not {} x {}", n, n);
    }
  }
  for (const Node& node : body.nodes) {
    std::string problem = CheckNode(node, n, body.node_positions.cols());
    if (!problem.empty()) return problem;
  }
  for (const ContactSurface& surface : body.surfaces) {
    std::string problem = CheckSurface(surface, n, body.node_positions.cols());
    if (!problem.empty()) return problem;
  }
  return CheckVisualSurface(body.visual_surface, body.node_positions.cols());
}

void CheckConsistent(const ReducedBody& body) {
  const std::string problem = FindInconsistency(body);
  FLEXMBS_CHECK(problem.empty(), fmt::format("reduced body '{}': {}", body.name, problem));
}

}  // namespace flexmbs::sid
