#pragma once

// Mirror symmetry of a set of points about the xy plane of their frame (z -> -z), and the
// reflection of nodal vector fields on them: shared by the reduction's equal-mode split
// (reduction/mirror_modes.h) and the planar check of a reduced body's modes (mbs/planar.cc).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace flexmbs {

/// For each point n (column of `p`, any length unit): the index of the point at (x, y, -z) within
/// `relative_distance` of the set's largest absolute coordinate (both rounded to that quantum),
/// or -1 where there is none. The set is mirror-symmetric about its xy plane when no entry is -1.
inline std::vector<Eigen::Index> MirrorPointsAboutXy(const Eigen::Matrix3Xd& p, double relative_distance) {
  const double quantum = relative_distance * std::max(1e-300, p.cwiseAbs().maxCoeff());
  const auto key = [&](double x, double y, double z) {
    return std::array<long long, 3>{std::llround(x / quantum), std::llround(y / quantum), std::llround(z / quantum)};
  };
  std::map<std::array<long long, 3>, Eigen::Index> by_position;
  for (Eigen::Index n = 0; n < p.cols(); ++n) by_position[key(p(0, n), p(1, n), p(2, n))] = n;
  std::vector<Eigen::Index> mirror(static_cast<std::size_t>(p.cols()), -1);
  for (Eigen::Index n = 0; n < p.cols(); ++n) {
    const auto found = by_position.find(key(p(0, n), p(1, n), -p(2, n)));
    if (found != by_position.end()) mirror[static_cast<std::size_t>(n)] = found->second;
  }
  return mirror;
}

/// P U: each column of U (3 per point, DOF 3 n + axis) reflected z -> -z on the points paired by
/// `mirror` (MirrorPointsAboutXy, no entry -1): (P u)_n = (u_x, u_y, -u_z) of u at mirror[n].
inline Eigen::MatrixXd ReflectedAboutXy(const std::vector<Eigen::Index>& mirror, const Eigen::MatrixXd& U) {
  Eigen::MatrixXd reflected(U.rows(), U.cols());
  for (std::size_t n = 0; n < mirror.size(); ++n) {
    const Eigen::Index from = 3 * mirror[n], to = 3 * static_cast<Eigen::Index>(n);
    reflected.row(to) = U.row(from);
    reflected.row(to + 1) = U.row(from + 1);
    reflected.row(to + 2) = -U.row(from + 2);
  }
  return reflected;
}

}  // namespace flexmbs
