// Time of the SID data of a reduced body against the size of the body and the number of modes
// n, stage by stage, with the measured scaling exponents (least-squares slopes of log(time)
// against log(DOF) at fixed n and against log(n) at fixed DOF). Each time is the fastest of
// --repeat runs (one run if it takes more than 2 s). Not a test: run it by hand (bench/README.md).
//
// 1. Inertia invariants (reduction/sid_invariants.h). Bodies: steel unit cubes of c x c x c
// structured cells, six tet10 each (tests/fem/test_meshes.h), DOF = 3 (2c + 1)^3, consistent
// mass; bases: n random fields (the cost does not depend on the values). N nodes,
// nnz(M_s) ~ 27 N for tet10, nnz(M) = 9 nnz(M_s):
//   scalar   ScalarMassMatrix: M_s out of M and the check M = M_s (x) I_3   O(nnz(M))
//   split    SplitModeComponents: Phi regrouped by component (a copy)       O(N n)
//   position ComputePositionMoments: M_s [1 r], then [1 r]^T M_s S          O(nnz(M_s) + N n)
//            (every order-0 block but Me)
//   modes    ComputeModeProducts: M_s S block by block (one pass over M_s)  O(nnz(M_s) n)
//            and the symmetric product S^T (M_s S), lower triangle only     + O(N n^2)
//   sparse   M_s S alone, whole, into a reused buffer: the share of the
//            sparse product in "modes"                                      O(nnz(M_s) n)
//   blocks   InvariantsFromMoments: the Taylor blocks                       O(n^2) entries
//   total    ComputeInertiaInvariants                                       O(nnz(M_s) n + N n^2)
//   peer     Phi^T (M Phi) with the full M: Me alone, the way a projection
//            of the full matrix computes it                                 O(nnz(M) n + N n^2)
//
// 2. Geometric stiffening (reduction/geometric_stiffening.h) of a held body: a steel bar
// 1 m x 0.2 m x 0.2 m of 5b x b x b structured cells, six tet10 each, DOF = 3 (10b + 1)(2b + 1)^2,
// clamped on x = 0, with one rigid marker on the tip face x = 1 m: C = 12 body + 6 marker load
// cases. Basis: n random fields zero on the clamp, M-orthonormal (the first n columns of one
// basis of the largest n). The stages of ComputeGeometricStiffening (P = 8 points per tet10,
// about 2 per DOF; nnz(L) the Cholesky factor's nonzeros, O(N^(4/3)) by nested dissection in 3-D):
//   loads     BuildStiffeningLoads: f = M b for 12 body cases, W^T per marker  O(nnz(M))
//   factor    K_oo = G^T K G, its Cholesky factor, the held check              O(N^2) flops (3-D ND)
//   solves    X = G K_oo^-1 G^T F for all C cases                              O(nnz(L) C)
// and the two ways of projecting K_G(sigma(x_c)) onto the basis (ProjectedStiffeningMatrices),
// each the other's peer in the same run, for the same X and Phi:
//   element   kElementByElement: per point the mode-gradient products (6 packed
//             triangles, 18 n^2 multiply-adds) times the 6 x C stresses         O(P n^2 (C + 6))
//   asm       fem::AssembleGeometricStiffness of all C cases alone: the
//             n-independent part of "assembled"                                 O(C nnz(K))
//   assembled kAssembled: per case K_G, its scalar part K_Gs, sum_a
//             Phi_a^T (K_Gs Phi_a)                                              O(C (nnz(K) + nnz(K_Gs) n + N n^2))
//   total     loads + factor + solves + the way kAuto picks
//             (AssembledProjectionIsFaster)
// ratio = element / assembled (> 1: assembled faster); diff = the largest |K0_assembled -
// K0_element|_F over the cases relative to the largest |K0_element|_F. Above DOF x n =
// --both-max-dof-modes only the way kAuto picks is timed (the other is "skipped").
//
//   bench_sid_invariants [--cells 9,16,23] [--bars 5,9,13] [--modes 10,20,50,100] [--repeat 3]
//                        [--both-max-dof-modes 3e7]
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bench/sid_bench_support.h"
#include "fem/assembly.h"
#include "fem/geometric_stiffness.h"
#include "reduction/basis_algebra.h"
#include "reduction/geometric_stiffening.h"
#include "reduction/interior_problem.h"
#include "reduction/sid_invariants.h"
#include "tests/fem/test_meshes.h"

namespace {

using Eigen::Index;
using flexmbs::bench::FastestSeconds;
using flexmbs::bench::TimeTable;
namespace fem = flexmbs::fem;
namespace reduction = flexmbs::reduction;

void InertiaInvariants(const std::vector<int>& cells, const std::vector<int>& modes, int repeat) {
  TimeTable table({"scalar", "split", "position", "modes", "sparse", "blocks", "total", "peer"}, modes);
  std::printf("Inertia invariants (unit cube, tet10)\n%8s %9s %4s", "DOF", "nnz(M)", "n");
  for (const std::string& name : table.stages) std::printf(" %9s", name.c_str());
  std::printf(" %10s   [s]\n", "peer/total");
  for (std::size_t s = 0; s < cells.size(); ++s) {
    const int c = cells[s];
    const fem::Mesh mesh =
        fem::testing::StructuredBox(fem::ElementType::kTet10, Eigen::Vector3i(c, c, c), Eigen::Vector3d(1.0, 1.0, 1.0))
            .mesh;
    const Eigen::SparseMatrix<double> M = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent).mass;
    table.AddSize(static_cast<double>(M.rows()));
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const Eigen::MatrixXd Phi = Eigen::MatrixXd::Random(M.rows(), modes[m]);
      Eigen::SparseMatrix<double> M_s;
      reduction::ModeComponents S, M_S;
      reduction::PositionMoments position;
      Eigen::MatrixXd P, Me;
      reduction::InertiaInvariants invariants;
      const std::function<void()> stages[] = {
          [&] { M_s = reduction::ScalarMassMatrix(M); },
          [&] { S = reduction::SplitModeComponents(Phi); },
          [&] { position = reduction::ComputePositionMoments(M_s, mesh.nodes, S); },
          [&] { P = reduction::ComputeModeProducts(M_s, S); },
          [&] { M_S.noalias() = M_s * S; },
          [&] { invariants = reduction::InvariantsFromMoments(position, P); },
          [&] { invariants = reduction::ComputeInertiaInvariants(M, mesh.nodes, Phi); },
          [&] { Me = Phi.transpose() * (M * Phi); }};
      std::printf("%8ld %9ld %4d", static_cast<long>(M.rows()), static_cast<long>(M.nonZeros()), modes[m]);
      for (std::size_t k = 0; k < table.stages.size(); ++k) {
        table.at(s, m, k) = FastestSeconds(repeat, stages[k]);
        std::printf(" %9.4f", table.at(s, m, k));
      }
      std::printf(" %10.2f\n", table.at(s, m, 7) / table.at(s, m, 6));
      std::fflush(stdout);
    }
  }
  table.PrintExponents({0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 4, 5, 6, 7});
}

// The bar of 5b x b x b cells, its matrices, the clamp and the tip marker.
struct HeldBar {
  fem::Mesh mesh;
  fem::SystemMatrices system;
  reduction::BoundaryConditions clamp;
  reduction::InterfaceSpec tip;
  reduction::FeModel model() const { return {system.stiffness, system.mass, mesh.nodes}; }
};

HeldBar MakeHeldBar(int b) {
  constexpr double kLength = 1.0, kSide = 0.2;
  HeldBar bar;
  bar.mesh = fem::testing::StructuredBox(fem::ElementType::kTet10, Eigen::Vector3i(5 * b, b, b),
                                         Eigen::Vector3d(kLength, kSide, kSide))
                 .mesh;
  bar.system = fem::AssembleSystem(bar.mesh, fem::MassMatrixKind::kConsistent);
  std::vector<int> root, tip;
  for (Index v = 0; v < bar.mesh.num_nodes(); ++v) {
    const double x = bar.mesh.nodes(0, v);
    if (x < 1e-9 * kLength) root.push_back(static_cast<int>(v));
    if (x > (1.0 - 1e-9) * kLength) tip.push_back(static_cast<int>(v));
  }
  bar.clamp.supports.push_back({"clamp", root});
  bar.tip = {"tip", tip, reduction::Coupling::kRigid, std::nullopt, {}};
  return bar;
}

void GeometricStiffening(const std::vector<int>& bars, const std::vector<int>& modes, int repeat,
                         double both_max_dof_modes) {
  using reduction::StiffeningProjection;
  enum Stage : std::size_t { kLoads, kFactor, kSolves, kElement, kAsm, kAssembled, kTotal };
  TimeTable table({"loads", "factor", "solves", "element", "asm", "assembled", "total"}, modes);
  std::printf("\nGeometric stiffening (clamped bar, tet10, one rigid tip marker)\n%8s %9s %3s %4s", "DOF", "nnz(K)",
              "C", "n");
  for (const std::string& name : table.stages) std::printf(" %9s", name.c_str());
  std::printf(" %6s %8s   [s]\n", "ratio", "diff");
  const int max_modes = *std::max_element(modes.begin(), modes.end());
  for (std::size_t s = 0; s < bars.size(); ++s) {
    const HeldBar bar = MakeHeldBar(bars[s]);
    const reduction::FeModel model = bar.model();
    const Index dofs = model.K().rows();
    table.AddSize(static_cast<double>(dofs));

    // The stages of SolveStaticResponses for a held body, timed one by one.
    Eigen::MatrixXd F, X;
    const double t_loads =
        FastestSeconds(repeat, [&] { F = reduction::BuildStiffeningLoads(model, std::span(&bar.tip, 1)); });
    std::optional<reduction::InteriorProblem> interior;
    std::optional<flexmbs::eigensolvers::ShiftedFactorization> factor;
    const double t_factor = FastestSeconds(1, [&] {
      interior = reduction::BuildInteriorProblem(model, bar.clamp);
      factor = reduction::FactorHeldInterior(model, bar.clamp, *interior);
    });
    const Eigen::SparseMatrix<double>& G = interior->transform.G;
    const double t_solves = FastestSeconds(repeat, [&] {
      const Eigen::MatrixXd rhs = Eigen::SparseMatrix<double>(G.transpose()) * F;
      X = G * factor->Solve(rhs);
    });
    factor.reset();
    const Eigen::MatrixXd Phi = reduction::MOrthonormalized(model.M(), G * Eigen::MatrixXd::Random(G.cols(), max_modes));

    // The assembly of K_G alone (the n-independent part of the assembled way).
    const double t_asm = FastestSeconds(repeat, [&] {
      for (Index c = 0; c < X.cols(); ++c) fem::AssembleGeometricStiffness(bar.mesh, X.col(c));
    });
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const Eigen::MatrixXd Phi_n = Phi.leftCols(modes[m]);
      const bool assembles = reduction::AssembledProjectionIsFaster(modes[m], X.cols());  // what kAuto picks
      const bool both = static_cast<double>(dofs) * modes[m] <= both_max_dof_modes;
      table.at(s, m, kLoads) = t_loads;
      table.at(s, m, kFactor) = t_factor;
      table.at(s, m, kSolves) = t_solves;
      table.at(s, m, kAsm) = t_asm;
      std::vector<Eigen::MatrixXd> K0_element, K0_assembled;
      for (const StiffeningProjection how : {StiffeningProjection::kElementByElement, StiffeningProjection::kAssembled}) {
        const bool picked = assembles == (how == StiffeningProjection::kAssembled);
        if (!both && !picked) continue;
        auto& K0 = how == StiffeningProjection::kAssembled ? K0_assembled : K0_element;
        table.at(s, m, how == StiffeningProjection::kAssembled ? kAssembled : kElement) = FastestSeconds(
            repeat, [&] { K0 = reduction::ProjectedStiffeningMatrices(bar.mesh, X, Phi_n, how); });
      }
      table.at(s, m, kTotal) =
          t_loads + t_factor + t_solves + table.at(s, m, assembles ? kAssembled : kElement);
      std::printf("%8ld %9ld %3ld %4d", static_cast<long>(dofs), static_cast<long>(model.K().nonZeros()),
                  static_cast<long>(X.cols()), modes[m]);
      for (std::size_t k = 0; k < table.stages.size(); ++k) {
        const double t = table.at(s, m, k);
        std::isfinite(t) ? std::printf(" %9.3f", t) : std::printf(" %9s", "skipped");
      }
      if (both) {
        double diff = 0.0, norm = 0.0;
        for (std::size_t c = 0; c < K0_element.size(); ++c) {
          diff = std::max(diff, (K0_assembled[c] - K0_element[c]).norm());
          norm = std::max(norm, K0_element[c].norm());
        }
        std::printf(" %6.2f %8.1e", table.at(s, m, kElement) / table.at(s, m, kAssembled), diff / norm);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  table.PrintExponents({kLoads, kFactor, kSolves, kElement, kAsm, kAssembled, kTotal}, {kElement, kAssembled, kTotal});
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> cells = {9, 16, 23};
  std::vector<int> bars = {5, 9, 13};
  std::vector<int> modes = {10, 20, 50, 100};
  int repeat = 3;
  double both_max_dof_modes = 3e7;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--cells" && has_value) {
      cells = flexmbs::bench::ParseList(argv[++i]);
    } else if (arg == "--bars" && has_value) {
      bars = flexmbs::bench::ParseList(argv[++i]);
    } else if (arg == "--modes" && has_value) {
      modes = flexmbs::bench::ParseList(argv[++i]);
    } else if (arg == "--repeat" && has_value) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--both-max-dof-modes" && has_value) {
      both_max_dof_modes = std::atof(argv[++i]);
    } else {
      flexmbs::bench::Fail(
          "usage: bench_sid_invariants [--cells 9,16,23] [--bars 5,9,13] [--modes 10,20,50,100] [--repeat 3] "
          "[--both-max-dof-modes 3e7]");
    }
  }
  InertiaInvariants(cells, modes, repeat);
  GeometricStiffening(bars, modes, repeat, both_max_dof_modes);
  return 0;
}
