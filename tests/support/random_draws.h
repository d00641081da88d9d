#pragma once
// Random vectors for tests drawn in a fixed order. The arguments of one call are evaluated in an
// unspecified order (GCC and clang differ), so Eigen::Vector3d(d(rng), d(rng), d(rng)) would set
// each compiler's test a different problem; these draw into named locals first (issue 19).

#include <Eigen/Core>

namespace flexmbs::testing {

/// Three draws of `distribution` from `rng`: x first, then y, then z.
template <typename Distribution, typename Engine>
Eigen::Vector3d DrawVector3(Distribution& distribution, Engine& rng) {
  const double x = distribution(rng);
  const double y = distribution(rng);
  const double z = distribution(rng);
  return Eigen::Vector3d(x, y, z);
}

}  // namespace flexmbs::testing
