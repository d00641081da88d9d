#include "mbs/mode_selection.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "core/error.h"
#include "core/skew.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

constexpr std::string_view kRigidKind = "rigid";
constexpr std::string_view kKeptKinds[] = {"normal", "constraint", "static_correction"};

[[noreturn]] void Fail(std::string_view body_name, std::string_view problem) {
  throw InputError(fmt::format("body '{}': modes: {}", body_name, problem));
}

std::string Describe(const sid::ReducedBody& body, Index i) {
  return fmt::format("mode {} ('{}')", i, body.mode_names[static_cast<std::size_t>(i)]);
}

bool IsRigid(const sid::ReducedBody& body, Index i) {
  return body.mode_kinds[static_cast<std::size_t>(i)] == kRigidKind;
}

/// "6 rigid, 4 normal": the body's modes per kind, for messages.
std::string KindCounts(const sid::ReducedBody& body) {
  std::map<std::string, int> counts;
  for (const std::string& kind : body.mode_kinds) ++counts[kind];
  std::string out;
  for (const auto& [kind, count] : counts) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", count, kind);
  return out.empty() ? "none" : out;
}

/// The column index of one listed mode, or Fail.
Index ResolveModeId(const sid::ReducedBody& body, const ModeId& id, std::string_view body_name) {
  const Index n = body.num_modes();
  if (const Index* index = std::get_if<Index>(&id)) {
    if (*index < 0 || *index >= n) {
      Fail(body_name, fmt::format("mode index {} out of range (the body has {} modes, 0 .. {})", *index, n, n - 1));
    }
    return *index;
  }
  const std::string& name = std::get<std::string>(id);
  const auto found = std::find(body.mode_names.begin(), body.mode_names.end(), name);
  if (found == body.mode_names.end()) {
    Fail(body_name, fmt::format("unknown mode '{}' (the body's modes are {})", name,
                                fmt::join(body.mode_names, ", ")));
  }
  return found - body.mode_names.begin();
}

std::vector<Index> SelectListed(const sid::ReducedBody& body, const std::vector<ModeId>& ids,
                                std::string_view body_name) {
  std::vector<Index> keep;
  for (const ModeId& id : ids) {
    const Index i = ResolveModeId(body, id, body_name);
    if (std::find(keep.begin(), keep.end(), i) != keep.end()) Fail(body_name, Describe(body, i) + " listed twice");
    if (IsRigid(body, i)) {
      Fail(body_name, Describe(body, i) + " is a rigid-body mode, which repeats the floating frame's motion: "
                                          "keep the body's elastic modes only");
    }
    keep.push_back(i);
  }
  std::sort(keep.begin(), keep.end());
  return keep;
}

/// The kinds a filter keeps (all non-rigid kinds if unset), or Fail.
std::vector<std::string> CheckedKinds(const std::optional<std::vector<std::string>>& kinds,
                                      std::string_view body_name) {
  if (!kinds) return {std::begin(kKeptKinds), std::end(kKeptKinds)};
  std::vector<std::string> out;
  for (const std::string& kind : *kinds) {
    if (kind == kRigidKind) {
      Fail(body_name, "kind 'rigid': rigid-body modes repeat the floating frame's motion; keep the elastic kinds");
    }
    if (std::find(std::begin(kKeptKinds), std::end(kKeptKinds), kind) == std::end(kKeptKinds)) {
      Fail(body_name, fmt::format("unknown mode kind '{}' (kinds: {})", kind, fmt::join(kKeptKinds, ", ")));
    }
    if (std::find(out.begin(), out.end(), kind) != out.end()) Fail(body_name, fmt::format("kind '{}' listed twice", kind));
    out.push_back(kind);
  }
  return out;
}

std::vector<Index> SelectFiltered(const sid::ReducedBody& body, const ModeSelection& selection,
                                  std::string_view body_name) {
  const std::vector<std::string> kinds = CheckedKinds(selection.kinds, body_name);
  if (selection.max_frequency_hz && !(std::isfinite(*selection.max_frequency_hz) && *selection.max_frequency_hz >= 0.0)) {
    Fail(body_name, fmt::format("max_frequency_hz {} must be finite and >= 0", *selection.max_frequency_hz));
  }
  std::vector<Index> keep;
  for (Index i = 0; i < body.num_modes(); ++i) {
    const std::string& kind = body.mode_kinds[static_cast<std::size_t>(i)];
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) continue;
    const double f = body.frequency_hz(i);
    if (selection.max_frequency_hz && !std::isnan(f) && f > *selection.max_frequency_hz) continue;
    keep.push_back(i);
  }
  return keep;
}

/// The indices of `width` consecutive entries per kept mode: k width .. k width + width - 1.
std::vector<Index> Expand(const std::vector<Index>& keep, Index width) {
  std::vector<Index> out;
  out.reserve(keep.size() * static_cast<std::size_t>(width));
  for (Index k : keep) {
    for (Index c = 0; c < width; ++c) out.push_back(k * width + c);
  }
  return out;
}

/// How a block's rows and columns index modes: rows one per mode (or not), columns `col_width`
/// per mode (0: not by mode).
struct ModeAxes {
  bool rows = false;
  Index col_width = 0;
};

MatrixXd RestrictMatrix(const MatrixXd& X, const std::vector<Index>& keep, ModeAxes axes) {
  if (X.size() == 0) return X;
  std::vector<Index> rows(static_cast<std::size_t>(X.rows())), cols(static_cast<std::size_t>(X.cols()));
  for (Index i = 0; i < X.rows(); ++i) rows[static_cast<std::size_t>(i)] = i;
  for (Index i = 0; i < X.cols(); ++i) cols[static_cast<std::size_t>(i)] = i;
  if (axes.rows) rows = keep;
  if (axes.col_width > 0) cols = Expand(keep, axes.col_width);
  return X(rows, cols);
}

sid::TaylorMatrix RestrictTaylor(const sid::TaylorMatrix& X, const std::vector<Index>& keep, Index n, ModeAxes axes) {
  sid::TaylorMatrix out;
  out.m0 = RestrictMatrix(X.m0, keep, axes);
  for (Index j : keep) {
    if (!X.m1.empty()) out.m1.push_back(RestrictMatrix(X.m1[static_cast<std::size_t>(j)], keep, axes));
    if (X.m2.empty()) continue;
    for (Index k : keep) out.m2.push_back(RestrictMatrix(X.m2[static_cast<std::size_t>(j * n + k)], keep, axes));
  }
  return out;
}

template <typename T>
std::vector<T> Pick(const std::vector<T>& list, const std::vector<Index>& keep) {
  std::vector<T> out;
  for (Index k : keep) out.push_back(list[static_cast<std::size_t>(k)]);
  return out;
}

Eigen::VectorXd PickEntries(const Eigen::VectorXd& v, const std::vector<Index>& keep) {
  return v.size() == 0 ? v : Eigen::VectorXd(v(keep));
}

}  // namespace

std::vector<Index> SelectModes(const sid::ReducedBody& body, const ModeSelection& selection,
                               std::string_view body_name) {
  std::vector<Index> keep;
  if (selection.modes) {
    if (selection.kinds || selection.max_frequency_hz) {
      Fail(body_name, "give either a list of modes or the filters kinds / max_frequency_hz, not both");
    }
    keep = SelectListed(body, *selection.modes, body_name);
  } else {
    keep = SelectFiltered(body, selection, body_name);
  }
  if (keep.empty()) Fail(body_name, fmt::format("the selection keeps none of the body's modes ({})", KindCounts(body)));
  return keep;
}

sid::ReducedBody RestrictModes(const sid::ReducedBody& body, const std::vector<Index>& keep) {
  const Index n = body.num_modes();
  for (std::size_t i = 0; i < keep.size(); ++i) {
    FLEXMBS_CHECK(keep[i] >= 0 && keep[i] < n, "mode index in range");
    FLEXMBS_CHECK(std::find(keep.begin() + static_cast<std::ptrdiff_t>(i) + 1, keep.end(), keep[i]) == keep.end(),
                  "distinct mode indices");
  }
  const ModeAxes none, rows{true, 0}, square{true, 1}, cols{false, 1}, blocks{false, 3}, rows_blocks{true, 3};
  sid::ReducedBody out;
  out.name = body.name;
  out.mass = body.mass;
  out.center_of_mass = body.center_of_mass;
  out.inertia_about_center_of_mass = body.inertia_about_center_of_mass;
  out.mode_names = Pick(body.mode_names, keep);
  out.mode_kinds = Pick(body.mode_kinds, keep);
  out.frequency_hz = PickEntries(body.frequency_hz, keep);
  out.relative_residuals = PickEntries(body.relative_residuals, keep);
  out.damping = body.damping;

  out.mdCM = RestrictTaylor(body.mdCM, keep, n, none);
  out.J = RestrictTaylor(body.J, keep, n, none);
  out.Ct = RestrictTaylor(body.Ct, keep, n, rows);
  out.Cr = RestrictTaylor(body.Cr, keep, n, rows);
  out.Me = RestrictTaylor(body.Me, keep, n, square);
  out.Gr = RestrictTaylor(body.Gr, keep, n, blocks);
  out.Ge = RestrictTaylor(body.Ge, keep, n, rows_blocks);
  out.Oe = RestrictTaylor(body.Oe, keep, n, rows);
  out.Ke = RestrictTaylor(body.Ke, keep, n, square);
  out.De = RestrictTaylor(body.De, keep, n, square);
  out.ksigma = RestrictTaylor(body.ksigma, keep, n, rows);
  if (!body.stiffening.empty()) {
    for (std::size_t a = 0; a < 3; ++a) {
      out.stiffening.K0t[a] = RestrictMatrix(body.stiffening.K0t[a], keep, square);
      out.stiffening.K0r[a] = RestrictMatrix(body.stiffening.K0r[a], keep, square);
    }
    for (std::size_t l = 0; l < 6; ++l) out.stiffening.K0omega[l] = RestrictMatrix(body.stiffening.K0omega[l], keep, square);
  }

  out.node_positions = body.node_positions;
  out.node_sets = body.node_sets;
  out.phi = RestrictMatrix(body.phi, keep, cols);
  for (const sid::Node& node : body.nodes) {
    sid::Node restricted = node;
    restricted.origin = RestrictTaylor(node.origin, keep, n, none);
    restricted.phi = RestrictTaylor(node.phi, keep, n, cols);
    restricted.psi = RestrictTaylor(node.psi, keep, n, cols);
    restricted.AP = RestrictTaylor(node.AP, keep, n, none);
    out.nodes.push_back(std::move(restricted));
  }
  for (const sid::ContactSurface& surface : body.surfaces) {
    sid::ContactSurface restricted = surface;
    restricted.phi = RestrictMatrix(surface.phi, keep, cols);
    out.surfaces.push_back(std::move(restricted));
  }
  out.visual_surface = body.visual_surface;
  out.provenance = body.provenance;
  return out;
}

namespace {

/// The generalised eigenproblem of MinimumDeformationShare, or nothing if Me is not positive
/// definite.
std::optional<Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>> DeformationShares(const sid::ReducedBody& body) {
  const MatrixXd& Me = body.Me.m0;
  if (Me.llt().info() != Eigen::Success) return std::nullopt;
  Eigen::Matrix<double, 6, 6> M_rr;
  const Eigen::Matrix3d S = Skew(body.mdCM.m0.col(0));
  M_rr << body.mass * Eigen::Matrix3d::Identity(), S.transpose(), S, body.J.m0;
  MatrixXd C(6, Me.rows());
  C << body.Ct.m0.transpose(), body.Cr.m0.transpose();
  MatrixXd Schur = Me - C.transpose() * M_rr.ldlt().solve(C);
  Schur = (0.5 * (Schur + Schur.transpose())).eval();
  return Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>(Schur, Me);
}

}  // namespace

double MinimumDeformationShare(const sid::ReducedBody& body) {
  if (body.num_modes() == 0) return 1.0;
  const auto solver = DeformationShares(body);
  FLEXMBS_CHECK(solver.has_value(), "Me positive definite");
  return solver->eigenvalues()(0);
}

void CheckNoRigidBodyMotion(const sid::ReducedBody& body, std::string_view body_name) {
  if (body.num_modes() == 0) return;
  const auto solver = DeformationShares(body);
  if (!solver) Fail(body_name, "the mode shapes are linearly dependent (Me is not positive definite)");
  const Eigen::VectorXd& shares = solver->eigenvalues();
  if (shares(0) >= kRigidMotionShare) return;
  // Participation of each mode in the rigid motions: sqrt(sum over rigid eigenvectors of
  // Me_ii x_i^2), so that modes of any scaling compare.
  Eigen::VectorXd participation = Eigen::VectorXd::Zero(shares.size());
  Index rigid_motions = 0;
  for (Index k = 0; k < shares.size() && shares(k) < kRigidMotionShare; ++k, ++rigid_motions) {
    participation += (solver->eigenvectors().col(k).array().square() * body.Me.m0.diagonal().array()).matrix();
  }
  participation = participation.cwiseSqrt();
  std::vector<std::string> names;
  for (Index i = 0; i < participation.size(); ++i) {
    if (participation(i) >= 0.1 * participation.maxCoeff()) names.push_back(body.mode_names[static_cast<std::size_t>(i)]);
  }
  Fail(body_name, fmt::format("{} combine into {} rigid-body motion{} (deformation share {:.1e} < {:.0e}), which the "
                              "floating frame already carries: leave rigid modes out, and the constraint modes of "
                              "one interface of an unsupported body (the frame is then held there)",
                              fmt::join(names, ", "), rigid_motions, rigid_motions > 1 ? "s" : "", shares(0),
                              kRigidMotionShare));
}

}  // namespace flexmbs::mbs
