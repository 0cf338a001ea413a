#include "controllers/theta_d.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "core/error.hpp"
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

// The design defaults come with the context, not from the controller: for the helicopter the
// paper's weights (Eqs. 33–34) and u0 = [m g, 0, 0, 0, 0], the rotor at hover thrust on the
// ground (spec §7.1).
const ControllerRegistration registration(
    "theta-d", "theta-D series T0 + ... + T_{N-1} around the initial state (paper-spec §5, §7)",
    [](const Settings& settings, const ControllerContext& context) -> std::unique_ptr<Controller> {
      settings.allow_only({theta_d_keys::terms, theta_d_keys::k, theta_d_keys::l, "fixed_point_iterations",
                           "fixed_point_tolerance", "Q", "R"});
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
      s.initial_input = defaults.input;
      if (context.settings_only) return nullptr;
      return std::make_unique<ThetaDController>(context.plant, std::move(s));
    });

// The paper's helicopter: its step runs on fixed-size views (ThetaDSettings::fixed_size).
constexpr int kFixedStates = 18;
constexpr int kFixedInputs = 5;

// A dynamic buffer seen as Rows × Cols at compile time where they are fixed (sizes checked by Eigen
// in debug builds); Eigen::Dynamic keeps it dynamic.
template <int Rows, int Cols>
Eigen::Map<Eigen::Matrix<double, Rows, Cols>> view(Eigen::MatrixXd& a) {
  return {a.data(), a.rows(), a.cols()};
}
template <int Rows, int Cols>
Eigen::Map<const Eigen::Matrix<double, Rows, Cols>> view(const Eigen::MatrixXd& a) {
  return {a.data(), a.rows(), a.cols()};
}
template <int Rows>
Eigen::Map<Eigen::Matrix<double, Rows, 1>> view(Eigen::VectorXd& a) {
  return {a.data(), a.size()};
}
template <int Rows>
Eigen::Map<const Eigen::Matrix<double, Rows, 1>> view(const Eigen::VectorXd& a) {
  return {a.data(), a.size()};
}

// Every entry exactly 0, by one vectorised sum of magnitudes: a sum of nonnegative terms is 0 only
// if each is (no underflow in adding them), and a NaN or an infinity makes it nonzero.
template <class Derived>
bool all_zero(const Eigen::MatrixBase<Derived>& a) {
  return a.cwiseAbs().sum() == 0.0;
}

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
  // Term i sums i + 2(i − 1) rank-m products (spec §5.4); the last term has the most.
  const Eigen::Index blocks = std::max(1, 3 * (settings_.terms - 1) - 2);
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
}

void ThetaDController::prepare_projections() {
  const Eigen::Index n = A0_.rows(), unknowns = n * (n + 1) / 2;
  // The projections pay when the fixed point may take several passes (spec §7.6) and their set-up
  // per step, rows·n per unknown, costs less than the partial solves they replace.
  input_rows_.clear();
  for (Eigen::Index r = 0; r < n; ++r)
    if (input_row_[static_cast<std::size_t>(r)]) input_rows_.push_back(r);
  const auto rows = static_cast<Eigen::Index>(input_rows_.size());
  const int passes = model_->sdc_depends_on_input() ? settings_.fixed_point_iterations : 1;
  project_last_term_ = settings_.terms >= 3 && passes > 1 && rows * (n + passes) < passes * input_row_unknowns_;
  if (!project_last_term_) return;
  std::vector<Eigen::Index> position(static_cast<std::size_t>(n * n));
  for (Eigen::Index a = 0; a < unknowns; ++a) {
    position[static_cast<std::size_t>(unknown_row_[a] * n + unknown_col_[a])] = a;
    position[static_cast<std::size_t>(unknown_col_[a] * n + unknown_row_[a])] = a;
  }
  row_solutions_.resize(unknowns, rows * n);
  for (Eigen::Index k = 0; k < rows; ++k)
    for (Eigen::Index j = 0; j < n; ++j)
      row_solutions_.col(k * n + j) =
          lyapunov_inverse_.row(position[static_cast<std::size_t>(input_rows_[static_cast<std::size_t>(k)] * n + j)])
              .transpose();
  projections_.resize(unknowns, rows);
  last_products_.resize(rows);
}

void ThetaDController::prepare_first_term_basis(const SdcPattern& pattern) {
  const Eigen::Index n = A0_.rows(), unknowns = n * (n + 1) / 2;
  // Eq. (22b) for a unit coefficient, W1 = M + Mᵀ with M = −T0 Ã + T0 g0 R⁻¹ g̃ᵀ T0:
  // Ã = e_r e_cᵀ gives M(:, c) = −T0(:, r); g̃ = e_r e_cᵀ gives M = (Y0 L⁻ᵀ(c, :)ᵀ) T0(r, :).
  Eigen::Index count = 0;
  for (const char varies : pattern.a_varies) count += varies;
  for (const char varies : pattern.g_varies) count += varies;
  basis_entries_.clear();
  a_basis_count_ = 0;
  a_unseen_.setOnes();
  g_unseen_.setOnes();
  if (count >= unknowns) {
    basis_.resize(unknowns, 0);
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
    M_.noalias() = (Y_[0] * R_inverse_sqrt_t_.row(c).transpose()) * T_[0].row(r);
    add_column();
  }
  basis_.noalias() = lyapunov_inverse_ * right_sides;
  coefficients_.resize(count);
}

template <int N, int M>
ThetaDController::Deviation ThetaDController::gather_deviation(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                                const Eigen::Ref<const Eigen::VectorXd>& input,
                                                                LastTerm wanted) {
  const Eigen::Index n = F_.rows();
  model_->sdc_varying(x, input, F_, B_);
  const auto F = view<N, N>(F_);
  const auto B = view<N, M>(B_);
  // Eq. (31) with θ = 1 (spec §5.7): Ã = F − A0 kept as its nonzero coefficients, g̃ = B − g0
  // scaled by L⁻ᵀ. T1 = e1 · basis_ · c needs every nonzero of Ã and g̃ to have a slot: one
  // vectorised comparison of the entries without one, then c read from its entries alone.
  Deviation deviation{all_zero((F - view<N, N>(A0_)).cwiseProduct(view<N, N>(a_unseen_))) &&
                          all_zero((B - view<N, M>(g0_)).cwiseProduct(view<N, M>(g_unseen_))),
                      wanted != LastTerm::full && T_.size() > 1 &&
                          all_zero(B.cwiseProduct(view<N, M>(outside_input_rows_)))};
  a_tilde_count_ = 0;
  auto add_a_tilde = [&](Eigen::Index entry, double value) {
    a_tilde_rows_[a_tilde_count_] = entry % n;
    a_tilde_cols_[a_tilde_count_] = entry / n;
    a_tilde_values_[a_tilde_count_++] = value;
  };
  if (deviation.in_basis) {
    for (Eigen::Index k = 0; k < coefficients_.size(); ++k) {
      const Eigen::Index entry = basis_entries_[static_cast<std::size_t>(k)];
      if (k < a_basis_count_) {
        coefficients_[k] = F_.data()[entry] - A0_.data()[entry];
        if (coefficients_[k] != 0.0) add_a_tilde(entry, coefficients_[k]);
      } else {
        coefficients_[k] = B_.data()[entry] - g0_.data()[entry];
      }
    }
  } else {
    for (Eigen::Index entry = 0; entry < n * n; ++entry) {
      const double value = F_.data()[entry] - A0_.data()[entry];
      if (value != 0.0) add_a_tilde(entry, value);
    }
  }
  auto g_tilde_scaled = view<N, M>(g_tilde_scaled_);
  g_tilde_scaled.noalias() = B * view<M, M>(R_inverse_sqrt_t_);
  g_tilde_scaled -= view<N, M>(g0_scaled_);
  view<N, M>(Z_[0]).noalias() = view<N, N>(T_[0]) * g_tilde_scaled;
  return deviation;
}

template <int N, int M>
void ThetaDController::form_right_side(std::size_t i) {
  const Eigen::Index n = F_.rows(), m = B_.cols(), unknowns = n * (n + 1) / 2;
  // Eqs. (22b–d) for general i (spec §5.4), W_i = M + Mᵀ with
  //   M = −T_{i−1} Ã + Σ_{j<i} T_j g0 R⁻¹ g̃ᵀ T_{i−1−j} + ½ Σ_{j≤i−2} T_j S2 T_{i−2−j} + ½ Σ_{1≤j<i} T_j G0 T_{i−j}:
  // the S1 sum is X + Xᵀ of its first half, the S2 and G0 sums are symmetric on their own.
  // S1, S2, G0 enter only through the rank-m factors Y_j = T_j g0 L⁻ᵀ and Z_j = T_j g̃ L⁻ᵀ,
  // gathered side by side so that the sums are one product.
  const auto previous = view<N, N>(T_[i - 1]);
  auto sum = view<N, N>(M_);
  sum.setZero();
  for (std::size_t k = 0; k < a_tilde_count_; ++k)
    sum.col(a_tilde_cols_[k]) -= a_tilde_values_[k] * previous.col(a_tilde_rows_[k]);
  auto left = view<N, Eigen::Dynamic>(left_);
  auto right = view<N, Eigen::Dynamic>(right_);
  Eigen::Index rank = 0;
  auto add = [&](double weight, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    left.template middleCols<M>(rank, m) = weight * view<N, M>(a);
    right.template middleCols<M>(rank, m) = view<N, M>(b);
    rank += m;
  };
  for (std::size_t j = 0; j < i; ++j) add(1.0, Y_[j], Z_[i - 1 - j]);
  for (std::size_t j = 0; j + 2 <= i; ++j) add(0.5, Z_[j], Z_[i - 2 - j]);
  for (std::size_t j = 1; j < i; ++j) add(0.5, Y_[j], Y_[i - j]);
  sum.noalias() += left.leftCols(rank) * right.leftCols(rank).transpose();
  for (Eigen::Index a = 0; a < unknowns; ++a)
    packed_right_[a] = sum(unknown_row_[a], unknown_col_[a]) + sum(unknown_col_[a], unknown_row_[a]);
}

template <int N, int M>
ThetaDController::LastTerm ThetaDController::evaluate_series(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                             const Eigen::Ref<const Eigen::VectorXd>& input, double t,
                                                             LastTerm wanted) {
  const Eigen::Index n = F_.rows(), unknowns = n * (n + 1) / 2;
  const Deviation deviation = gather_deviation<N, M>(x, input, wanted);
  for (std::size_t i = 1; i < T_.size(); ++i) {
    const bool last_term = i + 1 == T_.size();
    const LastTerm form = last_term && deviation.input_rows_only ? wanted : LastTerm::full;
    const Eigen::Index solved = form == LastTerm::input_rows ? input_row_unknowns_ : unknowns;
    // Eqs. (24)–(25): T_i Ac0 + Ac0ᵀ T_i = e_i(t) W_i.
    const double e = perturbation_factor(settings_.k[static_cast<Eigen::Index>(i - 1)],
                                         settings_.l[static_cast<Eigen::Index>(i - 1)], t - t0_);
    if (i == 1 && deviation.in_basis) {
      packed_term_.head(solved).noalias() = e * (basis_.topRows(solved) * coefficients_);
    } else {
      form_right_side<N, M>(i);
      if (form == LastTerm::input_row_products) {
        last_products_.noalias() = e * (projections_.transpose() * packed_right_);
        return form;
      }
      packed_term_.head(solved).noalias() = e * (lyapunov_inverse_.topRows(solved) * packed_right_);
    }
    if (form == LastTerm::input_rows) return form;
    auto term = view<N, N>(T_[i]);
    for (Eigen::Index a = 0; a < unknowns; ++a) {
      term(unknown_row_[a], unknown_col_[a]) = packed_term_[a];
      term(unknown_col_[a], unknown_row_[a]) = packed_term_[a];
    }
    if (last_term) break;  // Y, Z of the last term enter no W
    view<N, M>(Y_[i]).noalias() = term * view<N, M>(g0_scaled_);
    view<N, M>(Z_[i]).noalias() = term * view<N, M>(g_tilde_scaled_);
  }
  return LastTerm::full;
}

Eigen::MatrixXd ThetaDController::value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t) {
  require_reset("value_matrix");
  if (x.size() != F_.rows() || input.size() != B_.cols())
    throw Error("theta-d: value_matrix needs a state of " + std::to_string(F_.rows()) + " and an input of " +
                std::to_string(B_.cols()) + " entries");
  if (fixed_size_) evaluate_series<kFixedStates, kFixedInputs>(x, input, t, LastTerm::full);
  else evaluate_series<Eigen::Dynamic, Eigen::Dynamic>(x, input, t, LastTerm::full);
  Eigen::MatrixXd sum = T_[0];
  for (std::size_t i = 1; i < T_.size(); ++i) sum += T_[i];
  return sum;
}

void ThetaDController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                               const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  require_reset("control");
  model_->tracking_vector(measured_state, reference, v_);
  // Spec §7.6: start from the input applied at the previous sample.
  guess_ = applied_;
  if (fixed_size_) run_passes<kFixedStates, kFixedInputs>(t, measured_state);
  else run_passes<Eigen::Dynamic, Eigen::Dynamic>(t, measured_state);
  applied_ = guess_;
  u = guess_;
}

template <int N, int M>
void ThetaDController::run_passes(double t, const Eigen::Ref<const Eigen::VectorXd>& x) {
  // One pass is exact when the SDC does not depend on the input.
  const int passes = model_->sdc_depends_on_input() ? settings_.fixed_point_iterations : 1;
  const LastTerm wanted = project_last_term_ ? LastTerm::input_row_products : LastTerm::input_rows;
  const Eigen::Index n = v_.size();
  const auto v = view<N>(v_);
  // What every pass shares: v, hence T0 v and the forms that give the last term on the input rows.
  view<N>(T0_v_).noalias() = view<N, N>(T_[0]) * v;
  for (std::size_t k = 0; project_last_term_ && k < input_rows_.size(); ++k)
    projections_.col(static_cast<Eigen::Index>(k)).noalias() =
        row_solutions_.middleCols(static_cast<Eigen::Index>(k) * n, n) * v_;
  auto value_gradient = view<N>(value_gradient_);
  for (last_iterations_ = 1;; ++last_iterations_) {
    const LastTerm formed = evaluate_series<N, M>(x, guess_, t, wanted);
    // Eq. (35): u = −R⁻¹ Bᵀ(x) (Σ T_i) V_track.
    const std::size_t full_terms = formed == LastTerm::full ? T_.size() : T_.size() - 1;
    value_gradient = view<N>(T0_v_);
    for (std::size_t i = 1; i < full_terms; ++i) value_gradient.noalias() += view<N, N>(T_[i]) * v;
    // The last term on the input rows only: the rows of B(x) outside them are zero, so the
    // partial sums this leaves in the other entries of the gradient are multiplied by zero.
    if (formed == LastTerm::input_rows)
      for (Eigen::Index a = 0; a < input_row_unknowns_; ++a) {
        const Eigen::Index i = unknown_row_[a], j = unknown_col_[a];
        value_gradient[i] += packed_term_[a] * v[j];
        if (i != j) value_gradient[j] += packed_term_[a] * v[i];
      }
    if (formed == LastTerm::input_row_products)
      for (std::size_t k = 0; k < input_rows_.size(); ++k)
        value_gradient[input_rows_[k]] += last_products_[static_cast<Eigen::Index>(k)];
    view<M>(Bt_gradient_).noalias() = view<N, M>(B_).transpose() * value_gradient;
    view<M>(update_).noalias() = -view<M, M>(R_inverse_) * view<M>(Bt_gradient_);
    last_input_change_ = (update_ - guess_).cwiseAbs().maxCoeff();
    guess_ = update_;
    if (last_iterations_ >= passes || last_input_change_ < settings_.fixed_point_tolerance) break;
  }
}

}  // namespace thetad
