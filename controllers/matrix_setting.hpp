#pragma once

#include <string>

#include <Eigen/Core>

namespace thetad {

// Checks a matrix a controller was configured with against the plant's dimensions: throws
// thetad::Error "<controller>: <what> must be RxC, got rxc", or naming its non-finite entries.
void require_matrix_shape(const std::string& controller, const char* what, const Eigen::MatrixXd& matrix,
                          Eigen::Index rows, Eigen::Index cols);

}  // namespace thetad
