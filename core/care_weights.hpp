#pragma once

// What the CARE solvers (riccati.cpp, newton_kleinman.cpp) share: the checks of their inputs, the
// weights in the factored form they compute with, the residual, and the wording of their errors.
// The DARE solver (dare.cpp) shares the checks and the wording.

#include <string>

#include <Eigen/Dense>

namespace thetad::care {

using MatrixRef = Eigen::Ref<const Eigen::MatrixXd>;

std::string num(double value);  // %.3g
std::string shape(const MatrixRef& M);
[[noreturn]] void fail(const std::string& what);  // thetad::Error("CARE: " + what)
// thetad::Error(equation + ": " + what), equation "CARE" or "DARE".
[[noreturn]] void fail(const char* equation, const std::string& what);

// Appended to a failure that may come from a broken precondition the solver cannot name.
extern const char* const kStabilizabilityHint;

// Sizes match, nothing is empty, every entry is finite; the message names the matrix.
void check_inputs(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                  const char* equation = "CARE");
// The cross-term weight `name` (S, N) has B's shape and finite entries.
void check_cross_term(const char* name, const MatrixRef& S, const MatrixRef& B, const char* equation);
// M = M' to 1e-10 relative to ‖M‖_F: weights that differ by 1e7 within one matrix are normal here.
void check_symmetric(const char* name, const MatrixRef& M, const char* equation = "CARE");

// G = B R⁻¹ B' kept factored as W'W with W = L⁻¹B' (R = LL'): G·P then costs 2mn² instead of n³,
// P G P = (WP)'(WP) is exactly symmetric, and K = R⁻¹B'P = L'⁻¹(WP).
struct Weights {
  Eigen::MatrixXd Q;  // symmetrized
  double q_norm = 0.0;  // ‖Q‖_F (frobenius_norm), for the residuals measured against it
  Eigen::MatrixXd L;  // lower Cholesky factor of R
  Eigen::MatrixXd W;  // L⁻¹ B', m×n: set by set_input_matrix
};

// The equation with its cross term S (cost x'Qx + u'Ru + 2x'Su) eliminated: with u = v − R⁻¹S'x the
// cost is that of Ā = A − BR⁻¹S' and Q̄ = Q − SR⁻¹S', the Riccati solution is the same, and the gain
// is K̄ + R⁻¹S'. Used by the CARE and the DARE alike; R nonsingular (its LDL' given).
struct WithoutCrossTerm {
  Eigen::MatrixXd A;       // Ā
  Eigen::MatrixXd Q;       // Q̄, symmetrized
  Eigen::MatrixXd RinvSt;  // R⁻¹S'
};
WithoutCrossTerm eliminate_cross_term(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& S,
                                      const Eigen::LDLT<Eigen::MatrixXd>& R);

// Q and L once Q is symmetric positive semi-definite and R symmetric positive definite (the
// message gives the extreme eigenvalues otherwise).
Weights prepare_weights(const MatrixRef& Q, const MatrixRef& R);
// W = L⁻¹B'; allocates nothing once W has the size of B'.
void set_input_matrix(Weights& w, const MatrixRef& B);

// Res = A'P + PA − P G P + Q for symmetric P, with WP = W·P given. Returns ‖A'P‖_F, the size of
// one of the terms, for a caller that measures the residual against them (newton_kleinman.cpp).
double care_residual(const MatrixRef& A, const Weights& w, const Eigen::MatrixXd& P, const Eigen::MatrixXd& WP,
                   Eigen::MatrixXd& Res);

// The Newton steps add a Δ that is symmetric only up to rounding (the residual's GEMMs need not
// be): P stays exactly symmetric by averaging the pairs in place.
void symmetrize(Eigen::MatrixXd& P);
// ρ = ‖Res‖_F / (‖Q‖_F + 2‖A'P‖_F + ‖PGP‖_F): the residual against the terms that cancel in it.
// Not the normwise η below (‖A‖‖P‖ and ‖G‖‖P‖² in place of the terms): on the paper's problem P
// is large where G is small, ‖G‖‖P‖² overstates ‖PGP‖ by ten orders of magnitude and η is 1e-25
// for a P off by 1e-3 (measured), while ρ of the rounded exact solution is ~1e-16. A zero
// residual is ρ = 0 even when every term is zero too (Q = 0 and P = 0, the solution of a stable
// plant that Q does not weigh), not 0/0.
double residual_to_terms(double residual_norm, double q_norm, double AtP_norm, double PGP_norm);

// ‖M‖_F, also where Eigen's norm() fails: it sums the squares of the entries, so a matrix whose
// entries all lie below ~1e-154 has norm 0 and one with an entry above ~1e154 has norm ∞. The
// residual of an equation whose weights are scaled by 1e-170 would then read as converged, and one
// scaled by 1e200 as not finite. stableNorm() rescales, at a few times the cost, so it is taken only
// when norm() leaves the range where the sum of squares is exact to rounding.
double frobenius_norm(const MatrixRef& M);

// ‖Res‖_F / max(1, ‖Q‖_F): CareResult::relative_residual.
double relative_to_q(double residual_norm, const Weights& w);

// The normwise backward error η = ‖Res‖_F / (‖Q‖_F + 2‖A‖_F‖P‖_F + ‖G‖_F‖P‖_F²): the residual
// against the size of the terms that make it up, at rounding level for a backward-stable solution
// however ill-conditioned the equation is. ‖G‖_F = ‖W W'‖_F (an m×m product).
double normwise_residual(double residual_norm, double q_norm, double a_norm, double g_norm, double p_norm);

}  // namespace thetad::care
