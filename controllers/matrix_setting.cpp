#include "controllers/matrix_setting.hpp"

#include "core/error.hpp"

namespace thetad {

namespace {

std::string shape(Eigen::Index rows, Eigen::Index cols) { return std::to_string(rows) + "x" + std::to_string(cols); }

}  // namespace

void require_matrix_shape(const std::string& controller, const char* what, const Eigen::MatrixXd& matrix,
                          Eigen::Index rows, Eigen::Index cols) {
  if (matrix.rows() != rows || matrix.cols() != cols)
    throw Error(controller + ": " + what + " must be " + shape(rows, cols) + ", got " +
                shape(matrix.rows(), matrix.cols()));
  if (!matrix.allFinite()) throw Error(controller + ": " + what + " has non-finite entries");
}

}  // namespace thetad
