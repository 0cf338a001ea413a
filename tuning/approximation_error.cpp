#include "tuning/approximation_error.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/error.hpp"
#include "tuning/paired_bootstrap.hpp"
#include "core/parallel.hpp"
#include "tuning/sigma_fit.hpp"

namespace thetad::tuning {

ApproximationError approximation_error(const SdreController& sdre, const ThetaDController& theta_d,
                                       const TuningRecord& record, int threads) {
  if (record.shadow_inputs.cols() != record.size())
    throw Error("tuning: the record holds no theta-d inputs (fly it with the theta-d as shadow)");
  const Eigen::Index K = record.size(), n = record.states.rows();
  ApproximationError error;
  error.time = record.time;
  error.frobenius.resize(K);
  error.sigma.resize(K);
  error.control.resize(K);
  error.sdre_inputs = record.inputs;
  error.theta_d_inputs = record.shadow_inputs;
  const Eigen::MatrixXd R_sqrt = sdre.settings().R.llt().matrixU();  // ‖u‖_R = ‖U u‖ with R = UᵀU
  std::vector<ThetaDController> copies(static_cast<std::size_t>(std::max(1, threads)), theta_d);
  for_each_chunk(static_cast<std::size_t>(K), 64, std::max(1, threads), [&](int worker, std::size_t, std::size_t begin, std::size_t end) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(n);
    for (auto k = static_cast<Eigen::Index>(begin); k < static_cast<Eigen::Index>(end); ++k) {
      const double t = record.time[static_cast<std::size_t>(k)];
      const Eigen::MatrixXd P = sdre.value_matrix(record.states.col(k), record.inputs.col(k), t);
      const Eigen::MatrixXd S = copies[static_cast<std::size_t>(worker)].value_matrix(record.states.col(k), record.inputs.col(k), t);
      error.frobenius[k] = (S - P).norm() / P.norm();
      const double sigma_P = sigma_max_symmetric(solver, P);
      error.sigma[k] = std::abs(sigma_max_symmetric(solver, S) - sigma_P) / sigma_P;
      error.control[k] = (R_sqrt * (record.shadow_inputs.col(k) - record.inputs.col(k))).norm() /
                         (R_sqrt * record.inputs.col(k)).norm();
    }
  });
  return error;
}

std::string approximation_csv(const ApproximationError& error) {
  const Eigen::Index m = error.sdre_inputs.rows();
  std::string text = "t_s,frobenius_relative,sigma_relative,control_relative";
  for (Eigen::Index i = 0; i < m; ++i) text += ",u_sdre_" + std::to_string(i);
  for (Eigen::Index i = 0; i < m; ++i) text += ",u_theta_d_" + std::to_string(i);
  text += '\n';
  char number[32];
  const auto append = [&](double value) {
    std::snprintf(number, sizeof number, ",%.10g", value);
    text += number;
  };
  for (std::size_t k = 0; k < error.time.size(); ++k) {
    const auto column = static_cast<Eigen::Index>(k);
    std::snprintf(number, sizeof number, "%.6f", error.time[k]);
    text += number;
    append(error.frobenius[column]);
    append(error.sigma[column]);
    append(error.control[column]);
    for (Eigen::Index i = 0; i < m; ++i) append(error.sdre_inputs(i, column));
    for (Eigen::Index i = 0; i < m; ++i) append(error.theta_d_inputs(i, column));
    text += '\n';
  }
  return text;
}

nlohmann::ordered_json approximation_summary(const ApproximationError& error) {
  const auto quantiles = [](const Eigen::VectorXd& values) {
    const std::vector<double> list(values.data(), values.data() + values.size());
    return nlohmann::ordered_json{{"median", linear_quantile(list, 0.5)},
                                  {"p90", linear_quantile(list, 0.9)},
                                  {"max", values.maxCoeff()}};
  };
  return {{"samples", error.time.size()},
          {"frobenius", quantiles(error.frobenius)},
          {"sigma", quantiles(error.sigma)},
          {"control", quantiles(error.control)}};
}

}  // namespace thetad::tuning
