#pragma once

// The Riccati problems shared by riccati_bench (speed) and care_accuracy (forward error against
// 40-digit references): the paper's own, and random ones with the paper's weight spread.

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Dense>

namespace thetad::bench {

struct CareProblem {
  std::string name;
  Eigen::MatrixXd A, B, Q, R;
};

inline Eigen::MatrixXd random_normal(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd M(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) M(i, j) = normal(rng);
  return M;
}

// Diagonal weights 10^e, e uniform in [0, 7]: the paper's Q and R span the same seven decades.
inline Eigen::MatrixXd random_weights(Eigen::Index n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> exponent(0.0, 7.0);
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w(i) = std::pow(10.0, exponent(rng));
  return w.asDiagonal();
}

// A with N(0, 1/n) entries (some unstable modes), B with N(0, 1) entries: a random, generically
// controllable pair. Draws from rng in the order A, B, Q, R.
inline CareProblem random_care_problem(std::string name, Eigen::Index n, Eigen::Index m, std::mt19937_64& rng) {
  CareProblem p{std::move(name), {}, {}, {}, {}};
  p.A = random_normal(n, n, rng) / std::sqrt(static_cast<double>(n));
  p.B = random_normal(n, m, rng);
  p.Q = random_weights(n, rng);
  p.R = random_weights(m, rng);
  return p;
}

// The same A and B with Q = I and R = I: the usual random test problem of the CARE literature,
// whose Hamiltonian is far better scaled than with the paper's seven decades of weights. Draws
// from rng as random_care_problem does.
inline CareProblem unit_weight_care_problem(std::string name, Eigen::Index n, Eigen::Index m, std::mt19937_64& rng) {
  CareProblem p = random_care_problem(std::move(name), n, m, rng);
  p.Q = Eigen::MatrixXd::Identity(n, n);
  p.R = Eigen::MatrixXd::Identity(m, m);
  return p;
}

// random_care_problem in badly scaled state coordinates: x = D x̃ with D = diag(10^e), e uniform
// in [−2, 2], so that A = D⁻¹ Ã D has entries from about 1e-4 to 1e3 and B = D⁻¹ B̃; Q and R
// keep the paper's seven decades. Draws from rng in the order Ã, B̃, Q, R, D.
inline CareProblem diagonally_scaled_care_problem(std::string name, Eigen::Index n, Eigen::Index m,
                                                  std::mt19937_64& rng) {
  CareProblem p = random_care_problem(std::move(name), n, m, rng);
  std::uniform_real_distribution<double> exponent(-2.0, 2.0);
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) d(i) = std::pow(10.0, exponent(rng));
  p.A = d.cwiseInverse().asDiagonal() * p.A * d.asDiagonal();
  p.B = d.cwiseInverse().asDiagonal() * p.B;
  return p;
}

// A problem whose R is nearly singular, as CAREX 2.2: R = U diag(1, 10^−a, 10^−b) U' … with U a
// random rotation, a uniform in [0, 1] and κ(R) = 10^b, b uniform in [log10_kappa_low,
// log10_kappa_high]; A and B as above, Q = C'C with a random square C.
inline CareProblem ill_conditioned_r_problem(std::string name, Eigen::Index n, Eigen::Index m, double log10_kappa_low,
                                             double log10_kappa_high, std::mt19937_64& rng) {
  CareProblem p{std::move(name), {}, {}, {}, {}};
  p.A = random_normal(n, n, rng) / std::sqrt(static_cast<double>(n));
  p.B = random_normal(n, m, rng);
  const Eigen::MatrixXd C = random_normal(n, n, rng);
  p.Q = C.transpose() * C;
  const Eigen::MatrixXd U = random_normal(m, m, rng).householderQr().householderQ();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd d(m);
  d(0) = 1.0;
  for (Eigen::Index i = 1; i + 1 < m; ++i) d(i) = std::pow(10.0, -unit(rng));
  d(m - 1) = std::pow(10.0, -(log10_kappa_low + (log10_kappa_high - log10_kappa_low) * unit(rng)));
  p.R = U * d.asDiagonal() * U.transpose();
  p.R = 0.5 * (p.R + p.R.transpose()).eval();
  return p;
}

// ‖A'P + PA − PGP + Q‖_F / max(1, ‖Q‖_F), the normalisation of CareResult::relative_residual,
// computed the same way for every solver that a benchmark compares.
inline double relative_residual(const CareProblem& p, const Eigen::MatrixXd& P) {
  const Eigen::MatrixXd G = p.B * p.R.llt().solve(p.B.transpose());
  return (p.A.transpose() * P + P * p.A - P * G * P + p.Q).norm() / std::max(1.0, p.Q.norm());
}

// The helicopter at rest (docs/model.md §13: A0, g0) with the paper's weights (§7.2).
inline CareProblem paper_care_problem() {
  CareProblem p{"paper_n18_m5", Eigen::MatrixXd::Zero(18, 18), Eigen::MatrixXd::Zero(18, 5), {}, {}};
  const auto a = [&](int i, int j, double v) { p.A(i - 1, j - 1) = v; };
  a(1, 4, 1); a(2, 5, 1); a(3, 6, 1); a(4, 8, -9.81); a(5, 7, 9.81); a(5, 18, 6.3246e-6);
  a(6, 18, 9.84953); a(7, 10, 1); a(8, 11, 1); a(9, 12, 1); a(10, 14, 300);
  a(10, 18, 2.30496e-5); a(11, 13, 158.824); a(12, 18, -36.6771); a(13, 11, -1);
  a(13, 13, -10); a(14, 10, -1); a(14, 14, -10); a(15, 1, 1); a(16, 2, 1); a(17, 3, 1);
  a(18, 18, -0.1);
  const auto g = [&](int i, int j, double v) { p.B(i - 1, j - 1) = v; };
  g(5, 2, 5.4); g(6, 1, -0.121951); g(10, 2, 19.68); g(12, 2, -217.810); g(13, 4, 44.515);
  g(14, 5, 44.515);
  Eigen::VectorXd q(18);
  q << 1e4, 2e4, 1e7, 100, 100, 1, 100, 100, 1e3, 200, 1, 200, 1e5, 1e5, 2e3, 2e3, 1e6, 0;
  p.Q = q.asDiagonal();
  p.R = Eigen::Vector<double, 5>(1, 200, 1e7, 1e5, 1e5).asDiagonal();
  return p;
}

}  // namespace thetad::bench
