#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/log_column.hpp"

namespace thetad::sim {

// The logged controller samples of a run, row-major, columns.size() values per row. Reserved for
// the whole run before the first step (none for a summary-only run).
struct RunLog {
  std::vector<LogColumn> columns;
  std::vector<double> values;

  Eigen::Index rows() const {
    return columns.empty() ? 0 : static_cast<Eigen::Index>(values.size() / columns.size());
  }
  Eigen::Map<const Eigen::VectorXd> row(Eigen::Index i) const {
    const auto width = static_cast<Eigen::Index>(columns.size());
    return {values.data() + i * width, width};
  }
};

}  // namespace thetad::sim
