// Time of the SID inertia invariants (reduction/sid_invariants.h) against the size of the body
// and the number of modes, stage by stage, with the measured scaling exponents. Bodies: steel
// unit cubes of c x c x c structured cells, six tet10 each (tests/fem/test_meshes.h), DOF =
// 3 (2c + 1)^3, consistent mass; bases: n random fields (the cost does not depend on the values).
//
// Stages and their cost (N nodes, n modes, nnz(M_s) ~ 27 N for tet10, nnz(M) = 9 nnz(M_s)):
//   scalar   ScalarMassMatrix: M_s out of M and the check M = M_s (x) I_3   O(nnz(M))
//   split    SplitModeComponents: Phi regrouped by component (a copy)       O(N n)
//   position ComputePositionMoments: M_s [1 r], then [1 r]^T M_s S          O(nnz(M_s) + N n)
//            (every order-0 block but Me)
//   modes    ComputeModeProducts: M_s S block by block (one pass over M_s)  O(nnz(M_s) n)
//            and the symmetric product S^T (M_s S), lower triangle only     + O(N n^2)
//   sparse   M_s S alone, whole, into a reused buffer: the share of the
//            sparse product in "modes"                                      O(nnz(M_s) n)
//   blocks   InvariantsFromMoments: the Taylor blocks                       O(n^2) entries
//   peer     Phi^T (M Phi) with the full M: Me alone, the way a projection
//            of the full matrix computes it                                 O(nnz(M) n + N n^2)
// The exponents are least-squares slopes of log(time) against log(DOF) at fixed n and against
// log(n) at fixed DOF. Each time is the fastest of --repeat runs. Not a test: run it by hand.
//
//   bench_sid_invariants [--cells 9,16,23] [--modes 10,20,50,100] [--repeat 3]
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fem/assembly.h"
#include "reduction/sid_invariants.h"
#include "tests/fem/test_meshes.h"

namespace {

using flexmbs::reduction::ModeComponents;

[[noreturn]] void Fail(const std::string& message) {
  std::fprintf(stderr, "bench_sid_invariants: %s\n", message.c_str());
  std::exit(1);
}

std::vector<int> ParseList(const std::string& text) {
  std::vector<int> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(std::atoi(item.c_str()));
  for (int v : values) {
    if (v <= 0) Fail("list entries must be positive: " + text);
  }
  return values;
}

// The fastest of `repeat` runs of `f` [s].
double FastestSeconds(int repeat, const std::function<void()>& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// Least-squares slope of log(y) against log(x).
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  const auto k = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

constexpr int kNumStages = 8;
const char* const kStageNames[kNumStages] = {"scalar", "split", "position", "modes", "sparse", "blocks", "total", "peer"};

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> cells = {9, 16, 23};
  std::vector<int> modes = {10, 20, 50, 100};
  int repeat = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--cells" && i + 1 < argc) {
      cells = ParseList(argv[++i]);
    } else if (arg == "--modes" && i + 1 < argc) {
      modes = ParseList(argv[++i]);
    } else if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else {
      Fail("usage: bench_sid_invariants [--cells 9,16,23] [--modes 10,20,50,100] [--repeat 3]");
    }
  }

  // seconds[size][modes][stage]
  std::vector<std::vector<std::array<double, kNumStages>>> seconds(cells.size());
  std::vector<double> dofs;
  std::printf("%8s %9s %4s", "DOF", "nnz(M)", "n");
  for (const char* name : kStageNames) std::printf(" %9s", name);
  std::printf("   [s]\n");
  for (std::size_t s = 0; s < cells.size(); ++s) {
    const int c = cells[s];
    const flexmbs::fem::Mesh mesh =
        flexmbs::fem::testing::StructuredBox(flexmbs::fem::ElementType::kTet10, Eigen::Vector3i(c, c, c),
                                             Eigen::Vector3d(1.0, 1.0, 1.0))
            .mesh;
    const Eigen::SparseMatrix<double> M =
        flexmbs::fem::AssembleSystem(mesh, flexmbs::fem::MassMatrixKind::kConsistent).mass;
    dofs.push_back(static_cast<double>(M.rows()));
    for (const int n : modes) {
      const Eigen::MatrixXd Phi = Eigen::MatrixXd::Random(M.rows(), n);
      std::array<double, kNumStages> t{};
      Eigen::SparseMatrix<double> M_s;
      ModeComponents S;
      flexmbs::reduction::PositionMoments position;
      Eigen::MatrixXd P, Me;
      ModeComponents M_S;
      flexmbs::reduction::InertiaInvariants invariants;
      t[0] = FastestSeconds(repeat, [&] { M_s = flexmbs::reduction::ScalarMassMatrix(M); });
      t[1] = FastestSeconds(repeat, [&] { S = flexmbs::reduction::SplitModeComponents(Phi); });
      t[2] = FastestSeconds(repeat, [&] { position = flexmbs::reduction::ComputePositionMoments(M_s, mesh.nodes, S); });
      t[3] = FastestSeconds(repeat, [&] { P = flexmbs::reduction::ComputeModeProducts(M_s, S); });
      t[4] = FastestSeconds(repeat, [&] { M_S.noalias() = M_s * S; });
      t[5] = FastestSeconds(repeat, [&] { invariants = flexmbs::reduction::InvariantsFromMoments(position, P); });
      t[6] = FastestSeconds(repeat, [&] { invariants = flexmbs::reduction::ComputeInertiaInvariants(M, mesh.nodes, Phi); });
      t[7] = FastestSeconds(repeat, [&] { Me = Phi.transpose() * (M * Phi); });
      seconds[s].push_back(t);
      std::printf("%8ld %9ld %4d", static_cast<long>(M.rows()), static_cast<long>(M.nonZeros()), n);
      for (double v : t) std::printf(" %9.4f", v);
      std::printf("\n");
      std::fflush(stdout);
    }
  }

  if (cells.size() > 1) {
    std::printf("\nexponent in DOF at fixed n\n%8s", "n");
    for (const char* name : kStageNames) std::printf(" %9s", name);
    std::printf("\n");
    for (std::size_t m = 0; m < modes.size(); ++m) {
      std::printf("%8d", modes[m]);
      for (int stage = 0; stage < kNumStages; ++stage) {
        std::vector<double> y;
        for (std::size_t s = 0; s < cells.size(); ++s) y.push_back(seconds[s][m][static_cast<std::size_t>(stage)]);
        std::printf(" %9.2f", Slope(dofs, y));
      }
      std::printf("\n");
    }
  }
  if (modes.size() > 1) {
    std::printf("\nexponent in n at fixed DOF\n%8s", "DOF");
    for (const char* name : kStageNames) std::printf(" %9s", name);
    std::printf("\n");
    std::vector<double> n_values(modes.begin(), modes.end());
    for (std::size_t s = 0; s < cells.size(); ++s) {
      std::printf("%8.0f", dofs[s]);
      for (int stage = 0; stage < kNumStages; ++stage) {
        std::vector<double> y;
        for (std::size_t m = 0; m < modes.size(); ++m) y.push_back(seconds[s][m][static_cast<std::size_t>(stage)]);
        std::printf(" %9.2f", Slope(n_values, y));
      }
      std::printf("\n");
    }
  }
  return 0;
}
