#include "controllers/theta_d_series.hpp"

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "controllers/theta_d.hpp"
#include "core/error.hpp"

namespace thetad {

double perturbation_factor(double k, double l, double elapsed) { return 1.0 - k * std::exp(-l * elapsed); }

double SeriesExpansion::coefficient(std::size_t j, const Eigen::Ref<const Eigen::VectorXd>& e) const {
  double product = 1.0;
  for (std::size_t i = 0; i < powers[j].size(); ++i)
    for (int p = 0; p < powers[j][i]; ++p) product *= e[static_cast<Eigen::Index>(i)];
  return product;
}

Eigen::MatrixXd SeriesExpansion::evaluate(const Eigen::Ref<const Eigen::VectorXd>& e) const {
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(pieces.front().rows(), pieces.front().cols());
  for (std::size_t j = 0; j < pieces.size(); ++j) sum += coefficient(j, e) * pieces[j];
  return sum;
}

SeriesExpansion ThetaDController::series_expansion(const Eigen::VectorXd& x, const Eigen::VectorXd& input) {
  require_reset("series_expansion");
  const Eigen::Index n = F_.rows();
  if (x.size() != n || input.size() != B_.cols())
    throw Error("theta-d: series_expansion needs a state of " + std::to_string(n) + " and an input of " +
                std::to_string(B_.cols()) + " entries");
  // The recursion of docs/model.md §8.1 on polynomials in e: each T_i maps a monomial (its exponent
  // vector; std::map keeps the order, hence the pieces, deterministic) to its matrix.
  using Polynomial = std::map<std::vector<int>, Eigen::MatrixXd>;
  const SdcPlant::Coefficients sdc = model_->sdc(x, input);
  const Eigen::MatrixXd A_tilde = sdc.F - A0_;
  const Eigen::MatrixXd g_tilde_scaled = sdc.B * R_inverse_sqrt_t_ - g0_scaled_;
  const Eigen::MatrixXd S1 = g0_scaled_ * g_tilde_scaled.transpose() + g_tilde_scaled * g0_scaled_.transpose();
  const Eigen::MatrixXd S2 = g_tilde_scaled * g_tilde_scaled.transpose();
  const Eigen::MatrixXd G0 = g0_scaled_ * g0_scaled_.transpose();
  const std::size_t terms = T_.size();
  std::vector<Polynomial> T(terms);
  T[0].emplace(std::vector<int>(terms - 1, 0), T_[0]);

  const auto term_of = [n](Polynomial& W, const std::vector<int>& monomial) -> Eigen::MatrixXd& {
    return W.try_emplace(monomial, Eigen::MatrixXd::Zero(n, n)).first->second;
  };
  // W += a S b, monomials multiplying.
  const auto add_products = [&](Polynomial& W, const Polynomial& a, const Eigen::MatrixXd& S, const Polynomial& b) {
    for (const auto& [pa, A] : a)
      for (const auto& [pb, B] : b) {
        std::vector<int> monomial = pa;
        for (std::size_t i = 0; i < monomial.size(); ++i) monomial[i] += pb[i];
        term_of(W, monomial).noalias() += A * S * B;
      }
  };
  for (std::size_t i = 1; i < terms; ++i) {
    // W_i of docs/model.md §8.1 with the already scaled T_1 … T_{i−1}.
    Polynomial W;
    for (const auto& [p, C] : T[i - 1]) {
      Eigen::MatrixXd& w = term_of(W, p);
      w.noalias() -= C * A_tilde;
      w.noalias() -= A_tilde.transpose() * C;
    }
    for (std::size_t j = 0; j + 2 <= i; ++j) add_products(W, T[j], S2, T[i - 2 - j]);
    for (std::size_t j = 0; j < i; ++j) add_products(W, T[j], S1, T[i - 1 - j]);
    for (std::size_t j = 1; j < i; ++j) add_products(W, T[j], G0, T[i - j]);
    // T_i = e_i L⁻¹(W_i): the solver's Ac0ᵀX + XAc0 + Q = 0 with Q = −W. Each piece is symmetric
    // only up to rounding (the sums pair A S B with B S A), so it is symmetrized for the solver.
    for (const auto& [p, Wp] : W) {
      std::vector<int> monomial = p;
      ++monomial[i - 1];
      const Eigen::MatrixXd Q = -0.5 * (Wp + Wp.transpose());
      T[i].emplace(std::move(monomial), lyapunov_->solve(Q));
    }
  }
  SeriesExpansion expansion;
  for (Polynomial& term : T)
    for (auto& [p, C] : term) {
      expansion.powers.push_back(p);
      expansion.pieces.push_back(std::move(C));
    }
  return expansion;
}

}  // namespace thetad
