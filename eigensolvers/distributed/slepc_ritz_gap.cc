#include "eigensolvers/distributed/slepc_ritz_gap.h"

#include <algorithm>
#include <cmath>

namespace flexmbs::eigensolvers {
namespace {

// A Ritz value whose relative error estimate exceeds this says too little about where its
// eigenvalue is (its lower bound below tends to sigma as the estimate tends to 1).
constexpr double kRitzGuardMaxError = 1e-2;

}  // namespace

PetscErrorCode RecordRitzLowerBounds(EPS, PetscInt, PetscInt converged, PetscScalar* theta, PetscScalar*,
                                     PetscReal* error, PetscInt count, void* context) {
  auto* bounds = static_cast<RitzLowerBounds*>(context);
  try {
    bounds->lambda.clear();
    for (PetscInt i = converged; i < count; ++i) {
      if (!(error[i] <= kRitzGuardMaxError)) continue;
      PetscScalar value = theta[i] + error[i] * std::abs(theta[i]);
      PetscScalar imaginary = 0.0;
      const PetscErrorCode code = STBackTransform(bounds->st, 1, &value, &imaginary);
      if (code != 0) return code;
      bounds->lambda.push_back(value);
    }
  } catch (...) {
    return PETSC_ERR_MEM;
  }
  return 0;
}

Eigen::VectorXd ValuesForTheCut(const Eigen::VectorXd& converged, std::vector<double> ritz_lower) {
  const double largest = converged(converged.size() - 1);
  std::erase_if(ritz_lower, [&](double v) { return !(v > largest); });
  std::sort(ritz_lower.begin(), ritz_lower.end());
  Eigen::VectorXd values(converged.size() + static_cast<Eigen::Index>(ritz_lower.size()));
  values << converged, Eigen::Map<const Eigen::VectorXd>(ritz_lower.data(), static_cast<Eigen::Index>(ritz_lower.size()));
  return values;
}

}  // namespace flexmbs::eigensolvers
