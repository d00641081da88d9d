#include "eigensolvers/serial/block_lanczos_run.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/error.h"

namespace flexmbs::eigensolvers {
namespace {

// A residual within this many round-offs of applying T (eps ||T||) is as converged as the
// arithmetic allows. Deep in the spectrum of a slender body (mu 1e-7 of ||T||) a deflated run
// stalled at 0.3 eps ||T||, above 1e-10 mu; Rayleigh-Ritz and the refinement after the runs
// take such pairs to the residual bound.
constexpr double kRoundOffsOfT = 10.0;

}  // namespace

BlockRunResult RunBlockLanczos(const BlockKrylovSpace& space, const Eigen::MatrixXd& found,
                               Eigen::Index nev, const BlockRunOptions& options) {
  using Index = Eigen::Index;
  FLEXMBS_CHECK(nev >= 1 && options.block_size >= 1 && options.max_dimension >= nev &&
                    options.tolerance > 0.0,
                "RunBlockLanczos: bad nev or options");
  const Index n = space.local_rows();
  const Index p = std::min(options.block_size, space.global_rows() - found.cols());
  FLEXMBS_CHECK(p >= 1, "RunBlockLanczos: no direction outside the found modes");
  std::mt19937_64 rng(options.seed ^ space.stream());
  std::normal_distribution<double> normal;
  Eigen::MatrixXd start(n, p);
  for (Index i = 0; i < start.size(); ++i) start.data()[i] = normal(rng);
  DeflatedBlockLanczos lanczos(space, found, std::move(start));

  std::vector<Index> converged;
  for (;;) {
    const bool extended = lanczos.Extend();
    const Eigen::VectorXd& mu = lanczos.ritz_values();
    const Eigen::VectorXd residuals = lanczos.RitzResiduals();
    const Index candidates = std::min(nev, mu.size());
    const double norm = std::max(options.operator_norm, mu.size() > 0 ? std::abs(mu(0)) : 0.0);
    const double noise = kRoundOffsOfT * std::numeric_limits<double>::epsilon() * norm;
    converged.clear();
    for (Index j = 0; j < candidates; ++j) {
      if (residuals(j) <= std::max(options.tolerance * std::abs(mu(j)), noise))
        converged.push_back(j);
    }
    const bool done = static_cast<Index>(converged.size()) == nev;
    // An invariant space (no new direction) holds exact pairs: all of them are converged.
    if (done || !extended || lanczos.dimension() + p > options.max_dimension) break;
  }
  BlockRunResult result;
  result.vectors = lanczos.RitzVectors(converged);
  result.steps = lanczos.steps();
  result.columns = lanczos.columns_solved();
  return result;
}

}  // namespace flexmbs::eigensolvers
