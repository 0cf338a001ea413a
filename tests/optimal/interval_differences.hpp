#pragma once

// Central differences of a shooting interval's map, the yardstick for its exact derivatives.

#include <Eigen/Core>

#include "optimal/shooting_interval.hpp"
#include "tests/central_differences.hpp"

namespace thetad::testing {

// d(next node, cost)/d(node, u) by central differences of propagate() at z = (node, u), the node
// its first node_dim entries.
inline Eigen::MatrixXd interval_differences(ShootingInterval& interval, int k, const Eigen::VectorXd& z,
                                            Eigen::Index node_dim) {
  const Eigen::Index m = z.size() - node_dim;
  const auto map = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd result(node_dim + 1), next(node_dim);
    result[node_dim] = interval.propagate(k, at.head(node_dim), at.tail(m), next);
    result.head(node_dim) = next;
    return result;
  };
  return central_differences(map, z);
}

}  // namespace thetad::testing
