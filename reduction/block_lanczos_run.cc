#include "reduction/block_lanczos_run.h"

#include <algorithm>
#include <random>
#include <vector>

#include "core/error.h"

namespace flexmbs::reduction {

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
    converged.clear();
    for (Index j = 0; j < candidates; ++j) {
      if (residuals(j) <= options.tolerance * std::abs(mu(j))) converged.push_back(j);
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

}  // namespace flexmbs::reduction
