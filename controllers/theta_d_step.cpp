#include "controllers/theta_d.hpp"

// The per-step half of ThetaDController (theta_d.hpp): one pass of the series and the fixed point
// over it, compiled for the helicopter's fixed sizes and for dynamic ones; theta_d.cpp holds the
// settings and the design done at reset.

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad {

namespace {

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

// Twice a compile-time size (the n × 2m buffers of pairs of n × m factors); dynamic stays dynamic.
constexpr int twice(int size) { return size == Eigen::Dynamic ? Eigen::Dynamic : 2 * size; }

// Every entry exactly 0, by one vectorised sum of magnitudes: a sum of nonnegative terms is 0 only
// if each is (no underflow in adding them), and a NaN or an infinity makes it nonzero.
template <class Derived>
bool all_zero(const Eigen::MatrixBase<Derived>& a) {
  return a.cwiseAbs().sum() == 0.0;
}

// A fixed-size column split for product_columns: its longest run of a multiple of 8 rows, and the rest.
template <int N>
constexpr int kHeadRows = N / 8 * 8;
template <int N>
constexpr int kTailRows = N - kHeadRows<N>;

// sum = start + left · right column by column, right having as many rows as left has columns and
// start(j, head, tail) setting the rows of column j before the product is added. For a fixed
// number of rows N each column of the sum is accumulated in registers, its rows split into the
// longest run of a multiple of 8 and the rest: Eigen's own product at these sizes packs its
// operands (GEMM), and under AVX-512 Eigen uses 128-bit packets for a fixed 18-row vector (18 is a
// multiple of neither 8 nor 4), where the 16-row run takes 512-bit ones. Meant for the
// helicopter's N = 18: a much larger N would run out of registers.
template <int N, class Sum, class Left, class Right, class Start>
void product_columns(Sum&& sum, const Left& left, const Right& right, Start&& start) {
  static_assert(N >= 8 && N <= 32, "product_columns: a fixed N of 8 to 32 rows");
  eigen_assert(left.cols() == right.rows() && sum.cols() == right.cols());
  constexpr int kHead = kHeadRows<N>, kTail = kTailRows<N>;
  for (Eigen::Index j = 0; j < sum.cols(); ++j) {
    Eigen::Matrix<double, kHead, 1> head;
    Eigen::Matrix<double, kTail, 1> tail;
    start(j, head, tail);
    for (Eigen::Index k = 0; k < right.rows(); ++k) {
      head.noalias() += left.col(k).template head<kHead>() * right(k, j);
      tail.noalias() += left.col(k).template tail<kTail>() * right(k, j);
    }
    sum.col(j).template head<kHead>() = head;
    sum.col(j).template tail<kTail>() = tail;
  }
}

// sum += left · right (product_columns for a fixed N, Eigen's product for a dynamic one).
template <int N, class Sum, class Left, class Right>
void add_product(Sum&& sum, const Left& left, const Right& right) {
  if constexpr (N == Eigen::Dynamic) {
    sum.noalias() += left * right;
  } else {
    product_columns<N>(sum, left, right, [&](Eigen::Index j, auto& head, auto& tail) {
      head = sum.col(j).template head<kHeadRows<N>>();
      tail = sum.col(j).template tail<kTailRows<N>>();
    });
  }
}

}  // namespace

template <int N, int M>
ThetaDController::Deviation ThetaDController::gather_deviation(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                                const Eigen::Ref<const Eigen::VectorXd>& input) {
  const Eigen::Index n = F_.rows();
  model_->sdc_varying(x, input, F_, B_);
  const auto F = view<N, N>(F_);
  const auto B = view<N, M>(B_);
  // Eq. (31) with θ = 1 (docs/model.md §8.1): Ã = F − A0 kept as its nonzero coefficients, g̃ = B − g0
  // scaled by L⁻ᵀ. T1 = e1 · basis_ · c needs every nonzero of Ã and g̃ to have a slot: one
  // vectorised comparison of the entries without one, then c read from its entries alone.
  Deviation deviation{all_zero((F - view<N, N>(A0_)).cwiseProduct(view<N, N>(a_unseen_))) &&
                          all_zero((B - view<N, M>(g0_)).cwiseProduct(view<N, M>(g_unseen_))),
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
  if (T_.size() == 1) return deviation;
  product_rows_are_input_rows_ = deviation.input_rows_only;
  const std::vector<Eigen::Index>& rows = product_rows();
  const Eigen::Index m = B_.cols(), k = static_cast<Eigen::Index>(rows.size());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, twice(M)>> compact(compact_inputs_.data(), k, 2 * m);
  const auto g0_scaled = view<N, M>(g0_scaled_);
  for (Eigen::Index a = 0; a < k; ++a) {
    const Eigen::Index r = rows[static_cast<std::size_t>(a)];
    compact.row(a).template segment<M>(0, m) = g0_scaled.row(r);
    compact.row(a).template segment<M>(m, m).noalias() = B.row(r) * view<M, M>(R_inverse_sqrt_t_);
    compact.row(a).template segment<M>(m, m) -= g0_scaled.row(r);
  }
  form_products<N, M>(0);
  return deviation;
}

template <int N, int M>
void ThetaDController::form_products(std::size_t i) {
  const std::vector<Eigen::Index>& rows = product_rows();
  const Eigen::Index m = B_.cols(), k = static_cast<Eigen::Index>(rows.size());
  const auto term = view<N, N>(T_[i]);
  auto columns = view<N, Eigen::Dynamic>(product_columns_).leftCols(k);
  for (Eigen::Index a = 0; a < k; ++a) columns.col(a) = term.col(rows[static_cast<std::size_t>(a)]);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, twice(M)>> compact(compact_inputs_.data(), k, 2 * m);
  auto products = view<N, twice(M)>(products_[i]);
  // Y0 is the constant of reset(); a pass forms Z0 only.
  if (i == 0) {
    products.template rightCols<M>(m).setZero();
    add_product<N>(products.template rightCols<M>(m), columns, compact.template rightCols<M>(m));
  } else {
    products.setZero();
    add_product<N>(products, columns, compact);
  }
}

template <int N, int M>
void ThetaDController::form_right_side(std::size_t i) {
  const Eigen::Index n = F_.rows(), m = B_.cols(), unknowns = n * (n + 1) / 2;
  // Eqs. (22b–d) for general i (docs/model.md §8.1), W_i = M + Mᵀ with
  //   M = −T_{i−1} Ã + Σ_{j<i} T_j g0 R⁻¹ g̃ᵀ T_{i−1−j} + ½ Σ_{j≤i−2} T_j S2 T_{i−2−j} + ½ Σ_{1≤j<i} T_j G0 T_{i−j}:
  // the S1 sum is X + Xᵀ of its first half, the S2 and G0 sums are symmetric on their own.
  // S1, S2, G0 enter only through the rank-m factors Y_j = T_j g0 L⁻ᵀ and Z_j = T_j g̃ L⁻ᵀ.
  // With C_j = Y_j + Z_{j−1} (j ≥ 1), Σ_{1≤j<i} C_j C_{i−j}ᵀ holds the G0 and S2 sums and every
  // S1 product but Y_0 Z_{i−1}ᵀ and its transpose (the coefficient of t^i in C(t) C(t)ᵀ, C(t) =
  // Σ C_j t^j), and it is symmetric, so that the same W_i comes from
  //   M = −T_{i−1} Ã + Y_0 Z_{i−1}ᵀ + Σ_{1≤j<i−j} C_j C_{i−j}ᵀ + ½ C_{i/2} C_{i/2}ᵀ (i even):
  // 1 + ⌊(i − 1)/2⌋ + [i even] rank-m products instead of 3i − 2 (2 for T2 instead of 4),
  // gathered side by side so that the sum is one product.
  const auto previous = view<N, N>(T_[i - 1]);
  auto sum = view<N, N>(M_);
  auto left = view<N, Eigen::Dynamic>(left_);
  auto right = view<N, Eigen::Dynamic>(right_);
  Eigen::Index rank = 0;
  auto add = [&](double weight, const auto& a, const auto& b) {
    left.template middleCols<M>(rank, m) = weight * a;
    right.template middleCols<M>(rank, m) = b;
    rank += m;
  };
  add(1.0, view<N, twice(M)>(products_[0]).template leftCols<M>(m), view<N, twice(M)>(products_[i - 1]).template rightCols<M>(m));
  for (std::size_t j = 1; j < i - j; ++j) add(1.0, view<N, M>(pairs_[j]), view<N, M>(pairs_[i - j]));
  if (i % 2 == 0) add(0.5, view<N, M>(pairs_[i / 2]), view<N, M>(pairs_[i / 2]));
  if constexpr (N == Eigen::Dynamic) {
    sum.setZero();
    for (std::size_t k = 0; k < a_tilde_count_; ++k)
      sum.col(a_tilde_cols_[k]) -= a_tilde_values_[k] * previous.col(a_tilde_rows_[k]);
    sum.noalias() += left.leftCols(rank) * right.leftCols(rank).transpose();
  } else {
    // −T_{i−1} Ã enters each column's registers before the rank-m products: gather_deviation lists
    // Ã column by column, so one pass over it serves the columns in order.
    std::size_t k = 0;
    product_columns<N>(sum, left.leftCols(rank), right.leftCols(rank).transpose(),
                       [&](Eigen::Index j, auto& head, auto& tail) {
                         head.setZero();
                         tail.setZero();
                         for (; k < a_tilde_count_ && a_tilde_cols_[k] == j; ++k) {
                           const auto column = previous.col(a_tilde_rows_[k]);
                           head -= a_tilde_values_[k] * column.template head<kHeadRows<N>>();
                           tail -= a_tilde_values_[k] * column.template tail<kTailRows<N>>();
                         }
                       });
    if (k != a_tilde_count_) throw Error("theta-d: the entries of Ã are not in column order");
  }
  for (Eigen::Index a = 0; a < unknowns; ++a)
    packed_right_[a] = sum(unknown_row_[a], unknown_col_[a]) + sum(unknown_col_[a], unknown_row_[a]);
}

template <int N, int M>
ThetaDController::LastTerm ThetaDController::evaluate_series(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                             const Eigen::Ref<const Eigen::VectorXd>& input, double t,
                                                             LastTerm wanted, bool later_pass) {
  const Eigen::Index n = F_.rows(), unknowns = n * (n + 1) / 2;
  const Deviation deviation = gather_deviation<N, M>(x, input);
  if (!deviation.in_basis) first_term_current_ = false;
  for (std::size_t i = 1; i < T_.size(); ++i) {
    const bool last_term = i + 1 == T_.size();
    const LastTerm form = last_term && deviation.input_rows_only ? wanted : LastTerm::full;
    const Eigen::Index solved = form == LastTerm::input_rows ? input_row_unknowns_ : unknowns;
    // Eqs. (24)–(25): T_i Ac0 + Ac0ᵀ T_i = e_i(t) W_i.
    const double e = perturbation_factor(settings_.k[static_cast<Eigen::Index>(i - 1)],
                                         settings_.l[static_cast<Eigen::Index>(i - 1)], t - t0_);
    if (i == 1 && deviation.in_basis && !last_term) {
      if (later_pass && first_term_current_) {
        // Same x and t as the last pass: only the coefficients that follow the input moved (the
        // helicopter's rotor speed: 12 of 33), and T1 is linear in them.
        for (Eigen::Index k = 0; k < coefficients_.size(); ++k) {
          const double change = coefficients_[k] - first_term_coefficients_[k];
          if (change != 0.0) first_term_.noalias() += (e * change) * basis_.col(k);
        }
      } else {
        first_term_product_.apply(e, coefficients_, first_term_);
      }
      first_term_coefficients_ = coefficients_;
      first_term_current_ = true;
    } else if (i == 1 && deviation.in_basis) {
      packed_term_.head(solved).noalias() = e * (basis_.topRows(solved) * coefficients_);
    } else {
      form_right_side<N, M>(i);
      if (form == LastTerm::input_row_products) {
        last_products_.noalias() = e * (projections_.transpose() * packed_right_);
        return form;
      }
      if (form == LastTerm::input_rows) last_term_.apply(e, packed_right_, packed_term_.head(solved));
      else packed_term_.noalias() = e * (lyapunov_inverse_ * packed_right_);
    }
    if (form == LastTerm::input_rows) return form;
    auto term = view<N, N>(T_[i]);
    const Eigen::VectorXd& packed = i == 1 && first_term_current_ ? first_term_ : packed_term_;
    for (Eigen::Index a = 0; a < unknowns; ++a) {
      term(unknown_row_[a], unknown_col_[a]) = packed[a];
      term(unknown_col_[a], unknown_row_[a]) = packed[a];
    }
    if (last_term) break;  // Y, Z of the last term enter no W
    const Eigen::Index m = B_.cols();
    form_products<N, M>(i);
    view<N, M>(pairs_[i]) = view<N, twice(M)>(products_[i]).template leftCols<M>(m) +
                            view<N, twice(M)>(products_[i - 1]).template rightCols<M>(m);
  }
  return LastTerm::full;
}

Eigen::MatrixXd ThetaDController::value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t) {
  require_reset("value_matrix");
  if (x.size() != F_.rows() || input.size() != B_.cols())
    throw Error("theta-d: value_matrix needs a state of " + std::to_string(F_.rows()) + " and an input of " +
                std::to_string(B_.cols()) + " entries");
  if (fixed_size_) evaluate_series<kFixedStates, kFixedInputs>(x, input, t, LastTerm::full, false);
  else evaluate_series<Eigen::Dynamic, Eigen::Dynamic>(x, input, t, LastTerm::full, false);
  Eigen::MatrixXd sum = T_[0];
  for (std::size_t i = 1; i < T_.size(); ++i) sum += T_[i];
  return sum;
}

void ThetaDController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                               const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  require_reset("control");
  model_->tracking_vector(measured_state, reference, v_);
  // docs/model.md §6.2: start from the input applied at the previous sample.
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
  const auto v = view<N>(v_);
  // What every pass shares: v, hence T0 v and the forms that give the last term on the input rows.
  view<N>(T0_v_).noalias() = view<N, N>(T_[0]) * v;
  if (project_last_term_) {
    supported_projections_.noalias() = row_solutions_ * v_;
    for (std::size_t k = 0; k < input_rows_.size(); ++k)
      for (Eigen::Index s = projection_offsets_[k]; s < projection_offsets_[k + 1]; ++s)
        projections_(projection_support_[static_cast<std::size_t>(s)], static_cast<Eigen::Index>(k)) =
            supported_projections_[s];
  }
  auto value_gradient = view<N>(value_gradient_);
  LastTerm formed = LastTerm::full;
  for (last_iterations_ = 1;; ++last_iterations_) {
    formed = evaluate_series<N, M>(x, guess_, t, wanted, last_iterations_ > 1);
    // Eq. (35): u = −R⁻¹ Bᵀ(x) (Σ T_i) V_track.
    const std::size_t full_terms = formed == LastTerm::full ? T_.size() : T_.size() - 1;
    value_gradient = view<N>(T0_v_);
    for (std::size_t i = 1; i < full_terms; ++i) value_gradient.noalias() += view<N, N>(T_[i]) * v;
    add_partial_last_term<N>(formed, value_gradient);
    view<M>(Bt_gradient_).noalias() = view<N, M>(B_).transpose() * value_gradient;
    view<M>(update_).noalias() = -view<M, M>(R_inverse_) * view<M>(Bt_gradient_);
    last_input_change_ = (update_ - guess_).cwiseAbs().maxCoeff();
    guess_ = update_;
    if (last_iterations_ >= passes || last_input_change_ < settings_.fixed_point_tolerance) break;
  }
  if (settings_.certificates) measure_last_term<N, M>(formed);
}

template <int N, class Gradient>
void ThetaDController::add_partial_last_term(LastTerm formed, Gradient&& gradient) const {
  const auto v = view<N>(v_);
  // The last term on the input rows only: the rows of B(x) outside them are zero, so the
  // partial sums this leaves in the other entries of the gradient are multiplied by zero.
  if (formed == LastTerm::input_rows)
    for (Eigen::Index a = 0; a < input_row_unknowns_; ++a) {
      const Eigen::Index i = unknown_row_[a], j = unknown_col_[a];
      gradient[i] += packed_term_[a] * v[j];
      if (i != j) gradient[j] += packed_term_[a] * v[i];
    }
  if (formed == LastTerm::input_row_products)
    for (std::size_t k = 0; k < input_rows_.size(); ++k)
      gradient[input_rows_[k]] += last_products_[static_cast<Eigen::Index>(k)];
}

template <int N, int M>
void ThetaDController::measure_last_term(LastTerm formed) {
  auto gradient = view<N>(last_term_gradient_);
  if (formed == LastTerm::full) {
    gradient.noalias() = view<N, N>(T_.back()) * view<N>(v_);
  } else {
    gradient.setZero();
    add_partial_last_term<N>(formed, gradient);
  }
  // u_{N−1} = −R⁻¹ Bᵀ T_{N−1} v, as u is formed from the whole sum (Eq. 35).
  view<M>(Bt_gradient_).noalias() = view<N, M>(B_).transpose() * gradient;
  auto last_input = view<M>(last_term_input_);
  last_input.noalias() = -view<M, M>(R_inverse_) * view<M>(Bt_gradient_);
  auto weighted = view<M>(weighted_input_);
  weighted.noalias() = view<M, M>(settings_.R) * last_input;
  const double last_norm = last_input.dot(weighted);
  weighted.noalias() = view<M, M>(settings_.R) * view<M>(guess_);
  last_term_ratio_ = std::sqrt(last_norm / view<M>(guess_).dot(weighted));
}

}  // namespace thetad
