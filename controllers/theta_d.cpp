#include "controllers/theta_d.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "controllers/feedforward_controller.hpp"
#include "controllers/matrix_setting.hpp"
#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "core/error.hpp"
#include "core/riccati.hpp"

namespace thetad {

namespace {

// Empty means "all 1" (docs/model.md §8.1); otherwise one entry per term beyond T0.
Eigen::VectorXd series_parameter(const char* what, const Eigen::VectorXd& given, int count) {
  if (given.size() == 0) return Eigen::VectorXd::Ones(count);
  if (given.size() != count)
    throw Error(std::string("theta-d: ") + what + " needs " + std::to_string(count) + " entries (one per term T1 … T" +
                std::to_string(count) + "), got " + std::to_string(given.size()));
  if (!given.allFinite()) throw Error(std::string("theta-d: ") + what + " has non-finite entries");
  return given;
}

// The design defaults come with the context, not from the controller: for the helicopter the
// paper's weights (Eqs. 33–34) and u0 = [m g, 0, 0, 0, 0], the rotor at hover thrust on the
// ground (docs/model.md §8.1).
const ControllerRegistration theta_d_registration = register_controller<ThetaDController>(
    "theta-D series T0 + ... + T_{N-1} around the initial state (docs/model.md §7, §8.1); settings: terms, k, l, "
    "fixed_point_iterations, fixed_point_tolerance, Q, R, feedforward (none|velocity|velocity+trim), "
    "certificates (off|on)",
    [](const Settings& settings, const ControllerContext& context) -> std::unique_ptr<Controller> {
      settings.allow_only({theta_d_keys::terms, theta_d_keys::k, theta_d_keys::l, "fixed_point_iterations",
                           "fixed_point_tolerance", "Q", "R", "feedforward", "certificates"});
      const DesignDefaults& defaults = context.defaults;
      ThetaDSettings s;
      // Bounded: each term is one more Lyapunov solve per pass and two more settings entries, so a
      // huge N (a typo, a fuzzer's 1005501) would hang the design; the paper uses 3.
      s.terms = settings.integer(theta_d_keys::terms, s.terms, 1, 20);
      const Eigen::VectorXd ones = Eigen::VectorXd::Ones(s.terms - 1);
      s.k = settings.vector(theta_d_keys::k, ones, s.terms - 1);
      s.l = settings.vector(theta_d_keys::l, ones, s.terms - 1, 0.0);
      s.fixed_point_iterations = settings.integer("fixed_point_iterations", s.fixed_point_iterations, 1, 100);
      s.fixed_point_tolerance = settings.number("fixed_point_tolerance", s.fixed_point_tolerance, 0.0);
      s.Q = settings.diagonal_weight("Q", defaults.state_weights, Settings::Weight::positive_semidefinite);
      s.R = settings.diagonal_weight("R", defaults.input_weights, Settings::Weight::positive_definite);
      s.certificates = settings.boolean("certificates", false);
      const FeedForward feedforward = read_feedforward(settings, FeedForward::none);
      // With the trim's input applied, the decision variable v = u − u_r starts from 0.
      s.initial_input = feedforward == FeedForward::velocity_trim ? Eigen::VectorXd::Zero(defaults.input.size())
                                                                  : defaults.input;
      if (context.settings_only) return nullptr;
      if (feedforward == FeedForward::none) return std::make_unique<ThetaDController>(context.plant, std::move(s));
      return std::make_unique<FeedForwardController>(
          error_form_of(context, feedforward, zero_design_point(context.plant)),
          [s](const SdcPlant& error_form) { return std::make_unique<ThetaDController>(error_form, s); });
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
  require_matrix_shape("theta-d", "Q", settings_.Q, n, n);
  require_matrix_shape("theta-d", "R", settings_.R, m, m);
  if (settings_.initial_input.size() == 0) settings_.initial_input = Eigen::VectorXd::Zero(m);
  require_matrix_shape("theta-d", "initial_input", settings_.initial_input, m, 1);

  // R = L Lᵀ once: every g R⁻¹ gᵀ below is a product of the scaled factors g L⁻ᵀ.
  const Eigen::LLT<Eigen::MatrixXd> llt(settings_.R);
  if (llt.info() != Eigen::Success || !settings_.R.isApprox(settings_.R.transpose()))
    throw Error("theta-d: R must be symmetric positive definite");
  R_inverse_ = llt.solve(Eigen::MatrixXd::Identity(m, m));
  R_inverse_sqrt_t_ = llt.matrixU().solve(Eigen::MatrixXd::Identity(m, m));  // (Lᵀ)⁻¹ = L⁻ᵀ

  F_.resize(n, n);
  B_.resize(n, m);
  for (Eigen::Index r = 0; r < n; ++r) every_row_.push_back(r);
  compact_inputs_.resize(n, 2 * m);
  product_columns_.resize(n, n);
  const auto entries = static_cast<std::size_t>(n * n);
  a_tilde_rows_.resize(entries);
  a_tilde_cols_.resize(entries);
  a_tilde_values_.resize(entries);
  T_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, n));
  products_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, 2 * m));
  pairs_.assign(static_cast<std::size_t>(settings_.terms), Eigen::MatrixXd::Zero(n, m));
  M_.resize(n, n);
  // Term i sums 1 + ⌊(i − 1)/2⌋ + [i even] rank-m products (form_right_side); the last term has
  // the most.
  const int last = settings_.terms - 1;
  const Eigen::Index blocks = std::max(1, 1 + (last - 1) / 2 + (last % 2 == 0 ? 1 : 0));
  left_.resize(n, blocks * m);
  right_.resize(n, blocks * m);
  packed_right_.resize(n * (n + 1) / 2);
  packed_term_.resize(n * (n + 1) / 2);
  // Until reset() probes the plant (and for N = 1, which never asks): no coefficient in a
  // basis, every row an input row.
  input_row_.assign(static_cast<std::size_t>(n), 1);
  basis_.resize(n * (n + 1) / 2, 0);
  a_unseen_ = Eigen::MatrixXd::Ones(n, n);
  g_unseen_ = Eigen::MatrixXd::Ones(n, m);
  outside_input_rows_ = Eigen::MatrixXd::Zero(n, m);
  fixed_size_ = settings_.fixed_size && n == kFixedStates && m == kFixedInputs;
  v_.resize(n);
  T0_v_.resize(n);
  value_gradient_.resize(n);
  Bt_gradient_.resize(m);
  guess_.resize(m);
  update_.resize(m);
  applied_ = settings_.initial_input;
  if (settings_.certificates) {
    last_term_gradient_.resize(n);
    last_term_input_.resize(m);
    weighted_input_.resize(m);
  }
}

std::unique_ptr<Controller> ThetaDController::clone() const { return std::make_unique<ThetaDController>(*this); }

std::vector<ControllerColumn> ThetaDController::log_columns() const {
  if (!settings_.certificates) return {};
  return {{{"last_term_ratio", ""}, ControllerColumn::Worst::largest}};
}

void ThetaDController::log_values(std::vector<double>& row) const {
  if (settings_.certificates) row.push_back(last_term_ratio_);
}

void ThetaDController::reset(const Eigen::VectorXd& x0, double t0) {
  const Eigen::Index n = model_->state_dim();
  if (x0.size() != n) throw Error("theta-d: initial state has " + std::to_string(x0.size()) + " entries, the model " + std::to_string(n));
  t0_ = t0;
  // Eq. (31), docs/model.md §8.1: the system frozen at xa(t0), once.
  A0_.resize(n, n);
  g0_.resize(n, model_->input_dim());
  model_->sdc(x0, settings_.initial_input, A0_, g0_);
  // Eq. (22a).
  const CareResult care = solve_care(A0_, g0_, settings_.Q, settings_.R);
  T_[0] = care.P;
  g0_scaled_ = g0_ * R_inverse_sqrt_t_;
  products_[0].leftCols(g0_.cols()).noalias() = T_[0] * g0_scaled_;  // Y0
  Ac0_ = A0_ - g0_scaled_ * products_[0].leftCols(g0_.cols()).transpose();  // Ac0 = A0 − G0 T0
  Ac0_eigenvalues_ = Eigen::EigenSolver<Eigen::MatrixXd>(Ac0_, false).eigenvalues();
  if (settings_.terms > 1) {
    lyapunov_.emplace(Ac0_);
    prepare_series(x0);
  }
  // The entries of F and B that never change, once: each pass writes the others (sdc_varying).
  model_->sdc_constant(F_, B_);
  applied_ = settings_.initial_input;
  last_iterations_ = 0;
  last_input_change_ = 0.0;
}

void ThetaDController::require_reset(const char* caller) const {
  if (A0_.size() == 0) throw Error(std::string("theta-d: ") + caller + " called before reset()");
}

void ThetaDController::prepare_series(const Eigen::VectorXd& x0) {
  const SdcPattern pattern = probe_sdc(x0);
  input_row_ = pattern.input_row;
  for (Eigen::Index r = 0; r < A0_.rows(); ++r)
    outside_input_rows_.row(r).setConstant(input_row_[static_cast<std::size_t>(r)] ? 0.0 : 1.0);
  order_unknowns();
  prepare_projections();
  prepare_first_term_basis(pattern);
}

ThetaDController::SdcPattern ThetaDController::probe_sdc(const Eigen::VectorXd& x0) {
  const Eigen::Index n = A0_.rows(), m = g0_.cols();
  // Seen at x0 and at a few states and inputs around it. A coefficient missed here only costs
  // time: evaluate_series() notices it and takes the general path for that pass. The generator is
  // local and seeded because the probes are part of the set-up, not of the run's randomness.
  SdcPattern pattern{std::vector<char>(static_cast<std::size_t>(n * n), 0),
                     std::vector<char>(static_cast<std::size_t>(n * m), 0), std::vector<char>(static_cast<std::size_t>(n), 0)};
  std::mt19937_64 probe_generator(18);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd x = x0, input = settings_.initial_input;
  F_ = A0_;
  B_ = g0_;
  constexpr int kProbes = 4;
  for (int probe = 0; probe <= kProbes; ++probe) {
    if (probe > 0) {
      for (Eigen::Index j = 0; j < n; ++j) x[j] = x0[j] + 0.05 * (1.0 + std::abs(x0[j])) * unit(probe_generator);
      for (Eigen::Index j = 0; j < m; ++j)
        input[j] = settings_.initial_input[j] + 0.05 * (1.0 + std::abs(settings_.initial_input[j])) * unit(probe_generator);
      model_->sdc(x, input, F_, B_);
    }
    for (Eigen::Index j = 0; j < n * n; ++j)
      if (F_.data()[j] != A0_.data()[j]) pattern.a_varies[static_cast<std::size_t>(j)] = 1;
    for (Eigen::Index c = 0; c < m; ++c)
      for (Eigen::Index r = 0; r < n; ++r) {
        if (B_(r, c) != 0.0) pattern.input_row[static_cast<std::size_t>(r)] = 1;
        if (B_(r, c) != g0_(r, c)) pattern.g_varies[static_cast<std::size_t>(c * n + r)] = 1;
      }
  }
  return pattern;
}

void ThetaDController::order_unknowns() {
  const Eigen::Index n = A0_.rows(), unknowns = n * (n + 1) / 2;
  // The unknowns in the rows of B first, so that control() solves for a leading block only.
  unknown_row_.clear();
  unknown_col_.clear();
  for (const bool in_input_rows : {true, false}) {
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i <= j; ++i) {
        const bool touched = input_row_[static_cast<std::size_t>(i)] || input_row_[static_cast<std::size_t>(j)];
        if (touched != in_input_rows) continue;
        unknown_row_.push_back(i);
        unknown_col_.push_back(j);
      }
    if (in_input_rows) input_row_unknowns_ = static_cast<Eigen::Index>(unknown_row_.size());
  }
  // packed_inverse() solves Ac'X + XAc + Q = 0, i.e. X = L⁻¹(−Q).
  lyapunov_inverse_.resize(unknowns, unknowns);
  for (Eigen::Index b = 0; b < unknowns; ++b) {
    const Eigen::Index from_b = ConstantLyapunovSolver::packed_index(unknown_row_[b], unknown_col_[b]);
    for (Eigen::Index a = 0; a < unknowns; ++a)
      lyapunov_inverse_(a, b) =
          -lyapunov_->packed_inverse()(ConstantLyapunovSolver::packed_index(unknown_row_[a], unknown_col_[a]), from_b);
  }
  // Then the unknowns of each part grouped by the exact zeros of their rows of L⁻¹, so that the
  // partial solve (last_term_) and the T1 basis (first_term_product_) multiply only nonzero blocks.
  std::vector<Eigen::Index> order =
      ZeroPatternProduct::group_rows_by_pattern(lyapunov_inverse_.topRows(input_row_unknowns_));
  for (const Eigen::Index other :
       ZeroPatternProduct::group_rows_by_pattern(lyapunov_inverse_.bottomRows(unknowns - input_row_unknowns_)))
    order.push_back(input_row_unknowns_ + other);
  const std::vector<Eigen::Index> rows(unknown_row_), cols(unknown_col_);
  for (std::size_t k = 0; k < order.size(); ++k) {
    unknown_row_[k] = rows[static_cast<std::size_t>(order[k])];
    unknown_col_[k] = cols[static_cast<std::size_t>(order[k])];
  }
  lyapunov_inverse_ = Eigen::MatrixXd(lyapunov_inverse_(order, order));
  last_term_ = ZeroPatternProduct(lyapunov_inverse_.topRows(input_row_unknowns_));
}

void ThetaDController::prepare_projections() {
  const Eigen::Index n = A0_.rows(), unknowns = n * (n + 1) / 2;
  input_rows_.clear();
  for (Eigen::Index r = 0; r < n; ++r)
    if (input_row_[static_cast<std::size_t>(r)]) input_rows_.push_back(r);
  const auto rows = static_cast<Eigen::Index>(input_rows_.size());
  std::vector<Eigen::Index> position(static_cast<std::size_t>(n * n));
  for (Eigen::Index a = 0; a < unknowns; ++a) {
    position[static_cast<std::size_t>(unknown_row_[a] * n + unknown_col_[a])] = a;
    position[static_cast<std::size_t>(unknown_col_[a] * n + unknown_row_[a])] = a;
  }
  // Form k is zero outside its support, the unknowns of W where one of its n rows of L⁻¹ is
  // nonzero: row_solutions_ holds the forms' supports one after the other.
  projection_support_.clear();
  projection_offsets_.assign(1, 0);
  std::vector<Eigen::Index> solution_rows;  // row of L⁻¹ for T(r_k, j), per form and j
  for (Eigen::Index k = 0; k < rows; ++k) {
    for (Eigen::Index j = 0; j < n; ++j)
      solution_rows.push_back(position[static_cast<std::size_t>(input_rows_[static_cast<std::size_t>(k)] * n + j)]);
    for (Eigen::Index b = 0; b < unknowns; ++b)
      for (Eigen::Index j = 0; j < n; ++j)
        if (lyapunov_inverse_(solution_rows[static_cast<std::size_t>(k * n + j)], b) != 0.0) {
          projection_support_.push_back(b);
          break;
        }
    projection_offsets_.push_back(static_cast<Eigen::Index>(projection_support_.size()));
  }
  // The projections pay when the fixed point may take several passes (docs/model.md §6.2) and their set-up
  // per step, n per entry of the supports, and their dense products per pass cost less than the
  // partial solves they replace. Those multiply only last_term_'s stored entries but cost about
  // 1.4 times as much per entry as a dense product (a gather and a call per block; measured on
  // the helicopter with Eigen's kernel, docs/performance.md; the register panels, padding and
  // all, measured faster than that kernel, so the rule errs towards the partial solves there).
  const auto support = static_cast<Eigen::Index>(projection_support_.size());
  const auto passes = static_cast<Eigen::Index>(model_->sdc_depends_on_input() ? settings_.fixed_point_iterations : 1);
  project_last_term_ = settings_.terms >= 3 && passes > 1 &&
                      10 * (support * n + passes * rows * unknowns) < 14 * passes * last_term_.stored_entries();
  if (!project_last_term_) return;
  row_solutions_.resize(support, n);
  for (Eigen::Index k = 0; k < rows; ++k)
    for (Eigen::Index s = projection_offsets_[static_cast<std::size_t>(k)]; s < projection_offsets_[static_cast<std::size_t>(k + 1)]; ++s)
      for (Eigen::Index j = 0; j < n; ++j)
        row_solutions_(s, j) = lyapunov_inverse_(solution_rows[static_cast<std::size_t>(k * n + j)],
                                                 projection_support_[static_cast<std::size_t>(s)]);
  supported_projections_.resize(support);
  projections_ = Eigen::MatrixXd::Zero(unknowns, rows);  // the entries off the supports stay zero
  last_products_.resize(rows);
}

void ThetaDController::prepare_first_term_basis(const SdcPattern& pattern) {
  const Eigen::Index n = A0_.rows(), unknowns = n * (n + 1) / 2;
  // Eq. (22b) for a unit coefficient, W1 = M + Mᵀ with M = −T0 Ã + T0 g0 R⁻¹ g̃ᵀ T0:
  // Ã = e_r e_cᵀ gives M(:, c) = −T0(:, r); g̃ = e_r e_cᵀ gives M = (Y0 L⁻ᵀ(c, :)ᵀ) T0(r, :).
  Eigen::Index count = 0;
  for (const char varies : pattern.a_varies) count += varies;
  for (const char varies : pattern.g_varies) count += varies;
  first_term_.resize(unknowns);
  first_term_coefficients_.resize(count < unknowns ? count : 0);
  first_term_current_ = false;
  basis_entries_.clear();
  a_basis_count_ = 0;
  a_unseen_.setOnes();
  g_unseen_.setOnes();
  if (count >= unknowns) {
    basis_.resize(unknowns, 0);
    first_term_product_ = ZeroPatternProduct(basis_);
    coefficients_.resize(0);
    return;
  }
  Eigen::MatrixXd right_sides(unknowns, count);
  Eigen::Index slot = 0;
  auto add_column = [&] {
    for (Eigen::Index a = 0; a < unknowns; ++a)
      right_sides(a, slot) = M_(unknown_row_[a], unknown_col_[a]) + M_(unknown_col_[a], unknown_row_[a]);
    ++slot;
  };
  for (std::size_t j = 0; j < pattern.a_varies.size(); ++j) {
    if (!pattern.a_varies[j]) continue;
    basis_entries_.push_back(static_cast<Eigen::Index>(j));
    a_unseen_.data()[j] = 0.0;
    ++a_basis_count_;
    const auto r = static_cast<Eigen::Index>(j) % n, c = static_cast<Eigen::Index>(j) / n;
    M_.setZero();
    M_.col(c) = -T_[0].col(r);
    add_column();
  }
  for (std::size_t j = 0; j < pattern.g_varies.size(); ++j) {
    if (!pattern.g_varies[j]) continue;
    basis_entries_.push_back(static_cast<Eigen::Index>(j));
    g_unseen_.data()[j] = 0.0;
    const auto r = static_cast<Eigen::Index>(j) % n, c = static_cast<Eigen::Index>(j) / n;
    M_.noalias() = (products_[0].leftCols(g0_.cols()) * R_inverse_sqrt_t_.row(c).transpose()) * T_[0].row(r);
    add_column();
  }
  basis_.noalias() = lyapunov_inverse_ * right_sides;
  first_term_product_ = ZeroPatternProduct(basis_);
  coefficients_.resize(count);
}

}  // namespace thetad
