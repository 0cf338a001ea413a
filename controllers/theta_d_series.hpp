#pragma once

// The θ–D series as a polynomial in its perturbation factors (docs/model.md §8.1), for the tuner: ΣT_i(x, t)
// is Σ_j (Π_i e_i(t)^powers[j][i]) pieces[j] with pieces that depend on the state alone, so one
// expansion per state gives ΣT for any k, l and t at the cost of a few additions.
// ThetaDController::series_expansion() computes it (theta_d_series.cpp); theta_d.hpp has the
// controller itself.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace thetad {

// e_i(t) = 1 − k_i exp(−l_i (t − t0)) of Eq. (25), at elapsed = t − t0.
double perturbation_factor(double k, double l, double elapsed);

// ΣT_i(x, t) as a polynomial in e_1(t) … e_{N−1}(t) (docs/model.md §8.1). T_i = e_i L⁻¹(W_i) and W_i is
// linear and bilinear in T_0 … T_{i−1}, so the sum is Σ_j (Π_i e_i^powers[j][i]) pieces[j] with
// pieces that depend on the state alone: computed once per state, ΣT for any k, l and t costs a
// few additions and no Lyapunov solve (the tuner's cheap exact evaluation). With N = 3 the pieces
// are T0, T1° (monomial e1), T2a (e2), T2b (e1 e2) and T2c (e1² e2).
struct SeriesExpansion {
  std::vector<std::vector<int>> powers;  // powers[j][i]: exponent of e_{i+1} in the monomial of pieces[j]
  std::vector<Eigen::MatrixXd> pieces;   // symmetric n×n; pieces[0] = T0 (the empty monomial)

  // Π_i e_i^powers[j][i] for e = (e_1 … e_{N−1}), by repeated products (exact for e = 0 or 1).
  double coefficient(std::size_t j, const Eigen::Ref<const Eigen::VectorXd>& e) const;
  // Σ_j coefficient(j, e) pieces[j].
  Eigen::MatrixXd evaluate(const Eigen::Ref<const Eigen::VectorXd>& e) const;
};

}  // namespace thetad
