#include "controllers/theta_d.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "controllers/registry.hpp"
#include "core/settings.hpp"
#include "core/error.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "core/riccati.hpp"

namespace thetad {

namespace {

std::string shape(Eigen::Index rows, Eigen::Index cols) { return std::to_string(rows) + "x" + std::to_string(cols); }

void require_shape(const char* what, const Eigen::MatrixXd& M, Eigen::Index rows, Eigen::Index cols) {
  if (M.rows() != rows || M.cols() != cols)
    throw Error(std::string("theta-d: ") + what + " must be " + shape(rows, cols) + ", got " + shape(M.rows(), M.cols()));
  if (!M.allFinite()) throw Error(std::string("theta-d: ") + what + " has non-finite entries");
}

// Empty means "all 1" (spec §7.4); otherwise one entry per term beyond T0.
Eigen::VectorXd series_parameter(const char* what, const Eigen::VectorXd& given, int count) {
  if (given.size() == 0) return Eigen::VectorXd::Ones(count);
  if (given.size() != count)
    throw Error(std::string("theta-d: ") + what + " needs " + std::to_string(count) + " entries (one per term T1 … T" +
                std::to_string(count) + "), got " + std::to_string(given.size()));
  if (!given.allFinite()) throw Error(std::string("theta-d: ") + what + " has non-finite entries");
  return given;
}

// The helicopter's defaults live here, in the factory, not in the controller: the paper's weights
// (Eqs. 33–34) and u0 = [m g, 0, 0, 0, 0], the rotor at hover thrust on the ground (spec §7.1).
const ControllerRegistration registration(
    "theta-d", "theta-D series T0 + ... + T_{N-1} around the initial state (paper-spec §5, §7)",
    [](const YAML::Node& node, const ControllerContext& context) -> std::unique_ptr<Controller> {
      const Settings settings(node);
      settings.allow_only({"terms", "k", "l", "fixed_point_iterations", "fixed_point_tolerance", "Q", "R"});
      ThetaDSettings s;
      s.terms = settings.integer("terms", s.terms, 1);
      const Eigen::VectorXd ones = Eigen::VectorXd::Ones(s.terms - 1);
      s.k = settings.vector("k", ones, s.terms - 1);
      s.l = settings.vector("l", ones, s.terms - 1, 0.0);
      s.fixed_point_iterations = settings.integer("fixed_point_iterations", s.fixed_point_iterations, 1);
      s.fixed_point_tolerance = settings.number("fixed_point_tolerance", s.fixed_point_tolerance, 0.0);
      s.Q = settings.diagonal_weight("Q", heli::paper_state_weights(), Settings::Weight::positive_semidefinite);
      s.R = settings.diagonal_weight("R", heli::paper_input_weights(), Settings::Weight::positive_definite);
      const heli::Parameters& p = context.model.parameters();
      s.initial_input = Eigen::VectorXd::Zero(context.model.input_dim());
      s.initial_input[heli::kTmr] = p.mass * p.gravity;
      return std::make_unique<ThetaDController>(context.model, std::move(s));
    });

}  // namespace

ThetaDController::ThetaDController(const SdcPlant& model, ThetaDSettings settings)
    : model_(&model), settings_(std::move(settings)) {
  const Eigen::Index n = model.state_dim(), m = model.input_dim();
  if (settings_.terms < 1) throw Error("theta-d: terms must be >= 1 (T0 alone), got " + std::to_string(settings_.terms));
  if (settings_.fixed_point_iterations < 1)
    throw Error("theta-d: fixed_point_iterations must be >= 1, got " + std::to_string(settings_.fixed_point_iterations));
  if (!(settings_.fixed_point_tolerance >= 0.0))
    throw Error("theta-d: fixed_point_tolerance must be >= 0, got " + std::to_string(settings_.fixed_point_tolerance));
  settings_.k = series_parameter("k", settings_.k, settings_.terms - 1);
  settings_.l = series_parameter("l", settings_.l, settings_.terms - 1);
  if ((settings_.l.array() < 0.0).any()) throw Error("theta-d: every l_i must be >= 0 (e_i must settle, Eq. 25)");
  require_shape("Q", settings_.Q, n, n);
  require_shape("R", settings_.R, m, m);
  if (settings_.initial_input.size() == 0) settings_.initial_input = Eigen::VectorXd::Zero(m);
  require_shape("initial_input", settings_.initial_input, m, 1);

  // R = L Lᵀ once: every g R⁻¹ gᵀ below is a product of the scaled factors g L⁻ᵀ.
  const Eigen::LLT<Eigen::MatrixXd> llt(settings_.R);
  if (llt.info() != Eigen::Success || !settings_.R.isApprox(settings_.R.transpose()))
    throw Error("theta-d: R must be symmetric positive definite");
  R_inverse_ = llt.solve(Eigen::MatrixXd::Identity(m, m));
  R_inverse_sqrt_t_ = llt.matrixU().solve(Eigen::MatrixXd::Identity(m, m));  // (Lᵀ)⁻¹ = L⁻ᵀ

  F_.resize(n, n);
  B_.resize(n, m);
  g_tilde_scaled_.resize(n, m);
  const auto entries = static_cast<std::size_t>(n * n);
  a_tilde_rows_.resize(entries);
  a_tilde_cols_.resize(entries);
  a_tilde_values_.resize(entries);
  T_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, n));
  Y_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, m));
  Z_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, m));
  M_.resize(n, n);
  W_.resize(n, n);
  v_.resize(n);
  value_gradient_.resize(n);
  Bt_gradient_.resize(m);
  guess_.resize(m);
  update_.resize(m);
  applied_ = settings_.initial_input;
}

std::unique_ptr<Controller> ThetaDController::clone() const { return std::make_unique<ThetaDController>(*this); }

void ThetaDController::reset(const Eigen::VectorXd& x0, double t0) {
  const Eigen::Index n = model_->state_dim();
  if (x0.size() != n) throw Error("theta-d: initial state has " + std::to_string(x0.size()) + " entries, the model " + std::to_string(n));
  t0_ = t0;
  // Eq. (31), spec §7.1: the system frozen at xa(t0), once.
  A0_.resize(n, n);
  g0_.resize(n, model_->input_dim());
  model_->sdc(x0, settings_.initial_input, A0_, g0_);
  // Eq. (22a).
  const CareResult care = solve_care(A0_, g0_, settings_.Q, settings_.R);
  T_[0] = care.P;
  g0_scaled_ = g0_ * R_inverse_sqrt_t_;
  Y_[0].noalias() = T_[0] * g0_scaled_;
  Ac0_ = A0_ - g0_scaled_ * Y_[0].transpose();  // Ac0 = A0 − G0 T0
  Ac0_eigenvalues_ = Eigen::EigenSolver<Eigen::MatrixXd>(Ac0_, false).eigenvalues();
  if (settings_.terms > 1) lyapunov_.emplace(Ac0_);
  applied_ = settings_.initial_input;
  last_iterations_ = 0;
  last_input_change_ = 0.0;
}

void ThetaDController::require_reset(const char* caller) const {
  if (A0_.size() == 0) throw Error(std::string("theta-d: ") + caller + " called before reset()");
}

void ThetaDController::evaluate_series(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       const Eigen::Ref<const Eigen::VectorXd>& input, double t) {
  const Eigen::Index n = F_.rows();
  model_->sdc(x, input, F_, B_);
  // Eq. (31) with θ = 1 (spec §5.7): Ã = F − A0 kept as its nonzero coefficients, g̃ = B − g0
  // scaled by L⁻ᵀ.
  a_tilde_count_ = 0;
  for (Eigen::Index c = 0; c < n; ++c)
    for (Eigen::Index r = 0; r < n; ++r) {
      const double value = F_(r, c) - A0_(r, c);
      if (value == 0.0) continue;
      a_tilde_rows_[a_tilde_count_] = r;
      a_tilde_cols_[a_tilde_count_] = c;
      a_tilde_values_[a_tilde_count_++] = value;
    }
  g_tilde_scaled_.noalias() = B_ * R_inverse_sqrt_t_;
  g_tilde_scaled_ -= g0_scaled_;
  Z_[0].noalias() = T_[0] * g_tilde_scaled_;

  // Eqs. (22b–d) for general i (spec §5.4), W_i = M + Mᵀ with
  //   M = −T_{i−1} Ã + Σ_{j<i} T_j g0 R⁻¹ g̃ᵀ T_{i−1−j} + ½ Σ_{j≤i−2} T_j S2 T_{i−2−j} + ½ Σ_{1≤j<i} T_j G0 T_{i−j}:
  // the S1 sum is X + Xᵀ of its first half, the S2 and G0 sums are symmetric on their own.
  // S1, S2, G0 enter only through the rank-m factors Y_j = T_j g0 L⁻ᵀ and Z_j = T_j g̃ L⁻ᵀ.
  for (std::size_t i = 1; i < T_.size(); ++i) {
    const Eigen::MatrixXd& previous = T_[i - 1];
    M_.setZero();
    for (std::size_t k = 0; k < a_tilde_count_; ++k)
      M_.col(a_tilde_cols_[k]) -= a_tilde_values_[k] * previous.col(a_tilde_rows_[k]);
    for (std::size_t j = 0; j < i; ++j) M_.noalias() += Y_[j] * Z_[i - 1 - j].transpose();
    for (std::size_t j = 0; j + 2 <= i; ++j) M_.noalias() += 0.5 * Z_[j] * Z_[i - 2 - j].transpose();
    for (std::size_t j = 1; j < i; ++j) M_.noalias() += 0.5 * Y_[j] * Y_[i - j].transpose();
    // Eqs. (24)–(25): T_i Ac0 + Ac0ᵀ T_i = e_i(t) W_i, i.e. the solver's Ac0ᵀX + XAc0 + Q = 0 with
    // Q = −e_i W_i.
    const double e = 1.0 - settings_.k[static_cast<Eigen::Index>(i - 1)] *
                               std::exp(-settings_.l[static_cast<Eigen::Index>(i - 1)] * (t - t0_));
    W_.noalias() = -e * M_;
    W_.noalias() -= e * M_.transpose();
    lyapunov_->solve(W_, T_[i]);
    Y_[i].noalias() = T_[i] * g0_scaled_;
    Z_[i].noalias() = T_[i] * g_tilde_scaled_;
  }
}

Eigen::MatrixXd ThetaDController::value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t) {
  require_reset("value_matrix");
  if (x.size() != F_.rows() || input.size() != B_.cols())
    throw Error("theta-d: value_matrix needs a state of " + std::to_string(F_.rows()) + " and an input of " +
                std::to_string(B_.cols()) + " entries");
  evaluate_series(x, input, t);
  Eigen::MatrixXd sum = T_[0];
  for (std::size_t i = 1; i < T_.size(); ++i) sum += T_[i];
  return sum;
}

void ThetaDController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                               const sim::Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  require_reset("control");
  model_->tracking_vector(measured_state, reference, v_);
  // Spec §7.6: start from the input applied at the previous sample; one pass is exact when the
  // SDC does not depend on the input.
  const int passes = model_->sdc_depends_on_input() ? settings_.fixed_point_iterations : 1;
  guess_ = applied_;
  for (last_iterations_ = 1;; ++last_iterations_) {
    evaluate_series(measured_state, guess_, t);
    // Eq. (35): u = −R⁻¹ Bᵀ(x) (Σ T_i) V_track.
    value_gradient_.noalias() = T_[0] * v_;
    for (std::size_t i = 1; i < T_.size(); ++i) value_gradient_.noalias() += T_[i] * v_;
    Bt_gradient_.noalias() = B_.transpose() * value_gradient_;
    update_.noalias() = -R_inverse_ * Bt_gradient_;
    last_input_change_ = (update_ - guess_).cwiseAbs().maxCoeff();
    guess_ = update_;
    if (last_iterations_ >= passes || last_input_change_ < settings_.fixed_point_tolerance) break;
  }
  applied_ = guess_;
  u = guess_;
}

}  // namespace thetad
