#include "reduction/sid_invariants.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <utility>

#include "core/error.h"
#include "eigensolvers/mass_operator.h"

namespace flexmbs::reduction {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// How far M may be from M_s (x) I_3, relative to max |M|: the three axes' entries are sums of
// the same element terms (bit-equal from fem::AssembleSystem); 1e-13 leaves room for a matrix
// summed in another order elsewhere, far below any real coupling.
constexpr double kKroneckerTolerance = 1e-13;

// Entries of one block of M_s S in ComputeModeProducts (8 MB): large enough for an efficient
// product, small enough to stay in the last-level cache.
constexpr Index kBlockEntries = Index{1} << 20;

// int r phi_j^T dm (3 x 3): entry (b, a) = int r_b phi_j,a dm.
Matrix3d PositionModeProduct(const PositionMoments& p, Index n, Index j) {
  Matrix3d D;
  for (Index b = 0; b < 3; ++b) {
    for (Index a = 0; a < 3; ++a) D(b, a) = p.position_mode_products(b, a * n + j);
  }
  return D;
}

// int phi_j phi_k^T dm (3 x 3): entry (a, b) = int phi_j,a phi_k,b dm.
Matrix3d ModeModeProduct(const MatrixXd& P, Index n, Index j, Index k) {
  Matrix3d Pjk;
  for (Index a = 0; a < 3; ++a) {
    for (Index b = 0; b < 3; ++b) Pjk(a, b) = P(a * n + j, b * n + k);
  }
  return Pjk;
}

// The n x n block of component pair (a, b): entry (j, k) = int phi_j,a phi_k,b dm.
auto ComponentBlock(const MatrixXd& P, Index n, Index a, Index b) { return P.block(a * n, b * n, n, n); }

// eps_abc A(b, c): the vector whose entry a is A(b, c) - A(c, b) for (a, b, c) cyclic; for
// A = int x y^T dm it is int x cross y dm.
Eigen::Vector3d CrossOfProduct(const Matrix3d& A) {
  return {A(1, 2) - A(2, 1), A(2, 0) - A(0, 2), A(0, 1) - A(1, 0)};
}

// tr(A) I - A: with A = int b a^T dm, the integral of a~ b~^T = (a . b) I - b a^T.
Matrix3d TraceMinus(const Matrix3d& A) { return A.trace() * Matrix3d::Identity() - A; }

sid::TaylorMatrix Order0(MatrixXd m0) { return {std::move(m0), {}, {}}; }

}  // namespace

Eigen::SparseMatrix<double> ScalarMassMatrix(const Eigen::SparseMatrix<double>& M) {
  std::optional<eigensolvers::ScalarMassSplit> split = eigensolvers::SplitScalarMass(M);
  FLEXMBS_CHECK(split.has_value(), "mass matrix must be 3N x 3N");
  FLEXMBS_CHECK(split->max_deviation <= kKroneckerTolerance * split->max_entry,
                fmt::format("the SID integrals need M = M_s (x) I_3: an entry deviates by {:.3g}, the largest "
                            "entry is {:.3g}",
                            split->max_deviation, split->max_entry));
  return std::move(split->M_s);
}

ModeComponents SplitModeComponents(const Eigen::MatrixXd& Phi) {
  FLEXMBS_CHECK(Phi.rows() % 3 == 0, "the basis must have 3 rows per node");
  const Index N = Phi.rows() / 3;
  ModeComponents S(N, 3 * Phi.cols());
  // Row-major 3N x n: entry (3 v + a, j) at (3 v + a) n + j = v (3 n) + a n + j, i.e. S(v, a n + j).
  Eigen::Map<RowMajorMatrix>(S.data(), Phi.rows(), Phi.cols()) = Phi;
  return S;
}

namespace {

// The fields 1, x, y, z at the nodes (N x 4).
RowMajorMatrix NodeFields(const Eigen::Matrix3Xd& nodes) {
  RowMajorMatrix fields(nodes.cols(), 4);
  fields.col(0).setOnes();
  fields.rightCols<3>() = nodes.transpose();
  return fields;
}

// The position moments from the fields (NodeFields), M_s times them and the mode components.
PositionMoments PositionMomentsFrom(const RowMajorMatrix& fields, const RowMajorMatrix& M_fields,
                                    const ModeComponents& S) {
  const Eigen::Matrix4d field_products = fields.transpose() * M_fields;
  const MatrixXd field_mode_products = M_fields.transpose() * S;  // 4 x 3n

  PositionMoments p;
  p.mass = field_products(0, 0);
  p.first_moment = field_products.block<3, 1>(1, 0);
  p.second_moment = field_products.block<3, 3>(1, 1);
  const Index n = S.cols() / 3;
  p.mode_integrals.resize(3, n);
  for (Index a = 0; a < 3; ++a) p.mode_integrals.row(a) = field_mode_products.block(0, a * n, 1, n);
  p.position_mode_products = field_mode_products.bottomRows(3);
  return p;
}

}  // namespace

PositionMoments ComputePositionMoments(const Eigen::SparseMatrix<double>& M_s, const Eigen::Matrix3Xd& nodes,
                                       const ModeComponents& S) {
  const Index N = M_s.rows();
  FLEXMBS_CHECK(nodes.cols() == N && S.rows() == N && S.cols() % 3 == 0,
                "position moments: M_s, the nodes and the mode components disagree in size");
  const RowMajorMatrix fields = NodeFields(nodes);
  return PositionMomentsFrom(fields, M_s * fields, S);
}

Eigen::MatrixXd ComputeModeProducts(const Eigen::SparseMatrix<double>& M_s, const ModeComponents& S) {
  FLEXMBS_CHECK(S.rows() == M_s.rows(), "mode products: M_s and the mode components disagree in size");
  // Node block by node block: rows [v, v + k) of M_s S (the columns of the symmetric M_s, so one
  // pass over them adds whole contiguous rows of the row-major S), then their share
  // S(v.., :)^T (M_s S)(v.., :) of the lower triangle (half the flops of a full product). One
  // block buffer, reused: no Phi-sized temporary, and the block is still in cache for the product.
  const Index block_rows = std::max<Index>(256, kBlockEntries / std::max<Index>(S.cols(), 1));
  ModeComponents M_S_block;
  MatrixXd P = MatrixXd::Zero(S.cols(), S.cols());
  for (Index v = 0; v < S.rows(); v += block_rows) {
    const Index k = std::min(block_rows, S.rows() - v);
    M_S_block.noalias() = M_s.middleCols(v, k).transpose() * S;
    P.triangularView<Eigen::Lower>() += S.middleRows(v, k).transpose() * M_S_block;
  }
  P = P.selfadjointView<Eigen::Lower>();
  return P;
}

InertiaInvariants InvariantsFromMoments(const PositionMoments& p, const Eigen::MatrixXd& P) {
  FLEXMBS_CHECK(P.rows() == P.cols() && P.rows() % 3 == 0 && p.mode_integrals.cols() * 3 == P.rows(),
                "invariants: position moments and mode products disagree in the number of modes");
  const Index n = P.rows() / 3;
  const auto num_modes = static_cast<std::size_t>(n);
  const auto& W = CentrifugalBasis();
  InertiaInvariants inv;
  inv.mass = p.mass;

  // Order 0 from the position moments.
  inv.mdCM = Order0(p.first_moment);
  inv.J = Order0(TraceMinus(p.second_moment));
  inv.Ct = Order0(p.mode_integrals.transpose());
  MatrixXd Cr0(n, 3), Oe0(n, 6), Gr0(3, 3 * n);
  for (Index j = 0; j < n; ++j) {
    const Matrix3d D = PositionModeProduct(p, n, j);  // int r phi_j^T dm
    Cr0.row(j) = CrossOfProduct(D).transpose();       // int r x phi_j dm
    // int phi_j^T W_l r dm = sum_ab W_l(a, b) int phi_j,a r_b dm = sum_ab W_l(a, b) D(b, a).
    for (Index l = 0; l < 6; ++l) Oe0(j, l) = W[static_cast<std::size_t>(l)].cwiseProduct(D.transpose()).sum();
    // 2 int r~^T phi_j~ dm = -2 int r~ phi_j~ dm = 2 (tr(D) I - int phi_j r^T dm).
    Gr0.block<3, 3>(0, 3 * j) = 2.0 * TraceMinus(D.transpose());
    // int (r~ phi_j~^T + phi_j~ r~^T) dm = 2 tr(D) I - D - D^T.
    inv.J.m1.push_back(TraceMinus(D) + TraceMinus(D.transpose()));
    inv.mdCM.m1.push_back(p.mode_integrals.col(j));
  }
  inv.Cr = Order0(Cr0);
  inv.Oe = Order0(Oe0);
  inv.Gr = Order0(Gr0);

  // From the mode products. cross[a](j, i) = int (phi_j x phi_i)_a dm = sum_bc eps_abc P^bc(j, i).
  inv.Me = Order0(ComponentBlock(P, n, 0, 0) + ComponentBlock(P, n, 1, 1) + ComponentBlock(P, n, 2, 2));
  std::array<MatrixXd, 3> cross;
  for (Index a = 0; a < 3; ++a) {
    const Index b = (a + 1) % 3, c = (a + 2) % 3;
    cross[static_cast<std::size_t>(a)] = ComponentBlock(P, n, b, c) - ComponentBlock(P, n, c, b);
  }
  // centrifugal[l](i, j) = int phi_i^T W_l phi_j dm = sum_ab W_l(a, b) P^ab(i, j).
  std::array<MatrixXd, 6> centrifugal;
  for (std::size_t l = 0; l < 6; ++l) {
    centrifugal[l] = MatrixXd::Zero(n, n);
    for (Index a = 0; a < 3; ++a) {
      for (Index b = 0; b < 3; ++b) {
        if (W[l](a, b) != 0.0) centrifugal[l] += W[l](a, b) * ComponentBlock(P, n, a, b);
      }
    }
  }
  MatrixXd Ge0(n, 3 * n);
  inv.Cr.m1.resize(num_modes, MatrixXd(n, 3));
  inv.Oe.m1.resize(num_modes, MatrixXd(n, 6));
  inv.Gr.m1.resize(num_modes, MatrixXd(3, 3 * n));
  inv.J.m2.resize(num_modes * num_modes);
  for (Index j = 0; j < n; ++j) {
    const auto sj = static_cast<std::size_t>(j);
    // Row i of Cr m1[j] = (int phi_j x phi_i dm)^T; Ge_j = 2 int Phi^T phi_j~^T dm has the same rows.
    for (Index a = 0; a < 3; ++a) inv.Cr.m1[sj].col(a) = cross[static_cast<std::size_t>(a)].row(j).transpose();
    Ge0.block(0, 3 * j, n, 3) = 2.0 * inv.Cr.m1[sj];
    for (std::size_t l = 0; l < 6; ++l) inv.Oe.m1[sj].col(static_cast<Index>(l)) = centrifugal[l].col(j);
    for (Index k = 0; k < n; ++k) {
      const Matrix3d Pjk = ModeModeProduct(P, n, j, k);  // int phi_j phi_k^T dm
      // 2 int phi_k~^T phi_j~ dm = -2 int phi_k~ phi_j~ dm = 2 (tr(Pjk) I - Pjk).
      inv.Gr.m1[static_cast<std::size_t>(k)].block<3, 3>(0, 3 * j) = 2.0 * TraceMinus(Pjk);
      // 1/2 int (phi_j~ phi_k~^T + phi_k~ phi_j~^T) dm = tr(Pjk) I - (Pjk + Pjk^T) / 2.
      inv.J.m2[sj * num_modes + static_cast<std::size_t>(k)] =
          0.5 * (TraceMinus(Pjk) + TraceMinus(Pjk.transpose()));
    }
  }
  inv.Ge = Order0(Ge0);
  return inv;
}

InertiaInvariants ComputeInertiaInvariants(const Eigen::SparseMatrix<double>& M, const Eigen::Matrix3Xd& nodes,
                                           const Eigen::MatrixXd& Phi) {
  FLEXMBS_CHECK(M.rows() == 3 * nodes.cols() && Phi.rows() == M.rows(),
                "invariants: M, the nodes and the basis disagree in size");
  const Eigen::SparseMatrix<double> M_s = ScalarMassMatrix(M);
  const ModeComponents S = SplitModeComponents(Phi);
  return InvariantsFromMoments(ComputePositionMoments(M_s, nodes, S), ComputeModeProducts(M_s, S));
}

InertiaInvariants ComputeInertiaInvariants(const eigensolvers::SymmetricOperator& M, const Eigen::Matrix3Xd& nodes,
                                           const Eigen::MatrixXd& Phi) {
  const Index N = nodes.cols();
  FLEXMBS_CHECK(M.rows() == 3 * N && Phi.rows() == M.rows(), "invariants: M, the nodes and the basis disagree in size");
  // With M = M_s (x) I_3, M_s f for a nodal field f is M (f (x) e_x) at the x rows, and M_s S is
  // M Phi read as mode components.
  const RowMajorMatrix fields = NodeFields(nodes);
  MatrixXd on_x = MatrixXd::Zero(3 * N, 4);
  for (Index v = 0; v < N; ++v) on_x.row(3 * v) = fields.row(v);
  const MatrixXd M_on_x = M.Times(on_x);
  RowMajorMatrix M_fields(N, 4);
  for (Index v = 0; v < N; ++v) M_fields.row(v) = M_on_x.row(3 * v);
  const ModeComponents S = SplitModeComponents(Phi);
  const ModeComponents M_S = SplitModeComponents(M.Times(Phi));
  MatrixXd P = MatrixXd::Zero(S.cols(), S.cols());
  P.triangularView<Eigen::Lower>() = S.transpose() * M_S;
  P = P.selfadjointView<Eigen::Lower>();
  return InvariantsFromMoments(PositionMomentsFrom(fields, M_fields, S), P);
}

}  // namespace flexmbs::reduction
