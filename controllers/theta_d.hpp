#pragma once

// The θ–D controller (docs/model.md §7, §8.1): a series approximation Σ_{i<N} T_i(x, t) of the SDRE
// solution P(x) around the frozen system (A0, g0) = (F, B) at the initial state. T0 solves one
// CARE at reset; every further term solves a Lyapunov equation with the same constant operator
// L(T) = T Ac0 + Ac0ᵀ T, so one control step is a few products and N − 1 packed linear maps;
// T1 is one product with precomputed solutions, the last term is solved only where u needs it
// (docs/performance.md).
//
// Generic over any SdcPlant: it never knows which plant it flies.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "controllers/theta_d_series.hpp"
#include "core/lyapunov.hpp"
#include "core/sdc_plant.hpp"
#include "core/zero_pattern_product.hpp"

namespace thetad {

// The keys of the registered theta-d's settings block that a program writing one sets (`thetad
// tune` writes k, l and terms): defined here once, for the factory and the writers alike.
namespace theta_d_keys {
inline constexpr const char* terms = "terms";
inline constexpr const char* k = "k";
inline constexpr const char* l = "l";
}  // namespace theta_d_keys

struct ThetaDSettings {
  // N: the series T0 + T1 + … + T_{N−1} (docs/model.md §8.1: the paper uses N = 3). N ≥ 1.
  int terms = 3;
  // k_i, l_i of e_i(t) = 1 − k_i exp(−l_i (t − t0)) for i = 1 … N−1 (Eq. 25). Empty: all 1
  // (docs/model.md §8.1). k = 0 gives e_i ≡ 1, the plain series.
  Eigen::VectorXd k;
  Eigen::VectorXd l;
  // Weights of Eq. (14): Q n×n symmetric positive semi-definite, R m×m symmetric positive definite.
  Eigen::MatrixXd Q;
  Eigen::MatrixXd R;
  // u0, the input at which the initial SDC F(x0; u0), B(x0; u0) is evaluated, and the first guess
  // of the fixed point (docs/model.md §8.1, §6.2). Empty: zeros.
  Eigen::VectorXd initial_input;
  // Passes of the fixed point u -> F(x; u), B(x; u) -> u' for plants whose SDC depends on the
  // input (docs/model.md §6.2); 1 is the one-step-lag variant. Stops early when max|Δu| < tolerance.
  int fixed_point_iterations = 3;
  double fixed_point_tolerance = 1e-6;
  // Run the step on fixed-size Eigen types when the plant has the paper helicopter's dimensions
  // (n = 18, m = 5); false takes the dynamic-size path that serves every other plant. The same
  // arithmetic either way (a test compares the two); only the speed differs.
  bool fixed_size = true;
  // Log the last term's share of u at every sample (docs/model.md §8.4): ‖u_{N−1}‖_R / ‖u‖_R with
  // u_{N−1} = −R⁻¹ Bᵀ T_{N−1} V_track the last term's part of Eq. (35) and ‖u‖_R = √(uᵀ R u).
  bool certificates = false;
};

class ThetaDController final : public NamedController<"theta-d"> {
 public:
  // Keeps a reference to the model: it must outlive the controller and its clones.
  // Throws thetad::Error on settings that do not fit the model.
  ThetaDController(const SdcPlant& model, ThetaDSettings settings);

  std::unique_ptr<Controller> clone() const override;

  // Offline part of docs/model.md §8.1: A0, g0 at (x0; u0), T0 from (22a), Ac0 and its Lyapunov solver.
  // Throws thetad::Error when the CARE has no stabilizing solution at x0.
  void reset(const Eigen::VectorXd& x0, double t0) override;
  // Eq. (35) with the fixed point of docs/model.md §6.2. Allocates nothing.
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

  // Σ_{i<N} T_i(x, t) with F(x; input), B(x; input): the θ–D approximation of the SDRE's P(x),
  // by the same code as one pass of control(). terms() then holds the individual T_i.
  Eigen::MatrixXd value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t);

  // The pieces of Σ_{i<N} T_i(x, ·) with F(x; input), B(x; input) (docs/model.md §8.1): value_matrix(x,
  // input, t) equals series_expansion(x, input).evaluate(e(t)) with e_i = perturbation_factor(k_i,
  // l_i, t − start_time()), for any k, l. A cold path for the tuner: it allocates and solves one
  // Lyapunov equation per piece. Not thread-safe per object (the solver's buffers): one copy per thread.
  SeriesExpansion series_expansion(const Eigen::VectorXd& x, const Eigen::VectorXd& input);

  // Diagnostics (valid after reset()).
  double start_time() const { return t0_; }  // t0 of the last reset()
  // T_0 … T_{N−1} of the last value_matrix() (control() forms its last term only in the rows
  // that Bᵀ reads, and leaves T_{N−1} as it was).
  const std::vector<Eigen::MatrixXd>& terms() const { return T_; }
  const Eigen::MatrixXd& T0() const { return T_[0]; }
  const Eigen::MatrixXd& A0() const { return A0_; }
  const Eigen::MatrixXd& g0() const { return g0_; }
  const Eigen::MatrixXd& Ac0() const { return Ac0_; }
  const Eigen::VectorXcd& closed_loop_eigenvalues() const { return Ac0_eigenvalues_; }
  // Fixed-point passes of the last control() and the max|Δu| of its last pass.
  int last_iterations() const override { return last_iterations_; }
  double last_input_change() const { return last_input_change_; }
  const ThetaDSettings& settings() const { return settings_; }

  // With settings().certificates, the column last_term_ratio (largest is worst) and its value for
  // the last control(): 1 for N = 1 (T0 is the last term), NaN when u = 0.
  std::vector<ControllerColumn> log_columns() const override;
  void log_values(std::vector<double>& row) const override;

 private:
  void require_reset(const char* caller) const;
  // How much of the last term T_{N−1} a pass forms: all of it, into T_[N−1] (value_matrix); only
  // its unknowns in the rows that Bᵀ reads, left in packed_term_ (control: Eq. 35 needs nothing
  // else); or only (T_{N−1} v) on those rows, left in last_products_ (control, when the fixed
  // point makes several passes with one v: see projections_).
  enum class LastTerm { full, input_rows, input_row_products };
  // The step is one implementation compiled twice: for N × M known at compile time (the
  // helicopter's 18 × 5, on fixed-size views of the buffers below) and for Eigen::Dynamic.
  // One pass of docs/model.md §8.1 steps 1–2 at (x; input), time t: fills F_, B_, T_[1 … N−2] and the
  // last term as `wanted` asks if B(x) has no nonzero outside the input rows (else in full).
  // Returns the form it took. later_pass: a further fixed-point pass of one control(), at the x
  // and t of the last call (T1 is then updated from the coefficients that moved, see first_term_).
  template <int N, int M>
  LastTerm evaluate_series(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& input,
                           double t, LastTerm wanted, bool later_pass);
  // How F(x; input), B(x; input) differ from A0, g0, for one pass of evaluate_series().
  struct Deviation {
    bool in_basis;         // every nonzero of Ã and g̃ has a slot in basis_: T1 is one product
    bool input_rows_only;  // B has no nonzero outside the input rows: the last term may be partial
  };
  // Evaluates the SDC into F_, B_ and gathers Ã (a_tilde_*), c of basis_ (coefficients_), the
  // scaled inputs on the rows where B can be nonzero (compact_inputs_) and Z_[0].
  template <int N, int M>
  Deviation gather_deviation(const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& input);
  // [Y_i, Z_i] = T_i [g0 L⁻ᵀ, g̃ L⁻ᵀ] of this pass, from the columns of T_i in product_rows().
  template <int N, int M>
  void form_products(std::size_t i);
  // W_i of term i ≥ 1 from T_0 … T_{i−1}, packed into packed_right_ (through M_).
  template <int N, int M>
  void form_right_side(std::size_t i);
  // The fixed-point passes of control() on v_, from guess_ (docs/model.md §6.2).
  template <int N, int M>
  void run_passes(double t, const Eigen::Ref<const Eigen::VectorXd>& x);
  // Adds the last term's T v on the input rows, as a pass that formed it partially (`formed`, not
  // full) left it, to `gradient`.
  template <int N, class Gradient>
  void add_partial_last_term(LastTerm formed, Gradient&& gradient) const;
  // last_term_ratio_ of the pass that just ended, which formed the last term as `formed`.
  template <int N, int M>
  void measure_last_term(LastTerm formed);

  // The part of reset() that needs T0 and Ac0: the packed Lyapunov inverse in the order below and
  // the solutions T1 for each varying coefficient.
  void prepare_series(const Eigen::VectorXd& x0);
  // Which coefficients of F (column-major, n²) and B (n·m) vary and which rows of B can be nonzero.
  struct SdcPattern {
    std::vector<char> a_varies, g_varies, input_row;
  };
  SdcPattern probe_sdc(const Eigen::VectorXd& x0);
  // unknown_row_, unknown_col_, input_row_unknowns_, lyapunov_inverse_ and last_term_ from
  // input_row_ (the input-row unknowns grouped by the zero pattern of their rows of L⁻¹).
  void order_unknowns();
  // input_rows_ and, where they pay, the projections of the last term (see projections_).
  void prepare_projections();
  // basis_ and the entries a pass reads c from: T1 for each coefficient of `pattern` that varies.
  void prepare_first_term_basis(const SdcPattern& pattern);

  const SdcPlant* model_;
  ThetaDSettings settings_;
  double t0_ = 0.0;

  // Fixed at reset.
  Eigen::MatrixXd A0_, g0_, Ac0_;
  Eigen::VectorXcd Ac0_eigenvalues_;
  Eigen::MatrixXd R_inverse_;
  Eigen::MatrixXd R_inverse_sqrt_t_;  // L⁻ᵀ with R = L Lᵀ: g R⁻¹ gᵀ = (g L⁻ᵀ)(g L⁻ᵀ)ᵀ
  Eigen::MatrixXd g0_scaled_;         // g0 L⁻ᵀ: G0 = g0_scaled g0_scaledᵀ
  std::optional<ConstantLyapunovSolver> lyapunov_;
  // The n(n+1)/2 unknowns T(i, j), i ≤ j, of a symmetric term, ordered so that the first
  // input_row_unknowns_ are those in a row where B can be nonzero (input_row_, probed at reset).
  std::vector<Eigen::Index> unknown_row_, unknown_col_;
  Eigen::Index input_row_unknowns_ = 0;
  std::vector<char> input_row_;
  Eigen::MatrixXd lyapunov_inverse_;  // L⁻¹ on the unknowns in that order: T = L⁻¹ W
  // Its first input_row_unknowns_ rows without their exact zeros (the input-row unknowns come
  // grouped by zero pattern): the last term on the input rows.
  ZeroPatternProduct last_term_;
  // (T v)(r) = Σ_j v_j T(r, j) is, for each input row r, one fixed linear form of pack(W). With
  // several fixed-point passes on one v, control() forms these forms once, projections_.col(k)
  // (column k: T(r_k, ·) v), and each pass reads the last term on the input rows as
  // projections_ᵀ pack(W): ~rows·n(n+1) flops instead of the partial solve (last_term_). Only set
  // up when that is cheaper. Form k is nonzero only on its support, projection_support_[s] for s
  // in [projection_offsets_[k], projection_offsets_[k + 1]); there it is row_solutions_ · v, row s
  // holding, for j < n, the entry at that support of the row of L⁻¹ that gives T(r_k, j).
  std::vector<Eigen::Index> input_rows_;
  bool project_last_term_ = false;
  std::vector<Eigen::Index> projection_support_, projection_offsets_;
  Eigen::MatrixXd row_solutions_, projections_;
  Eigen::VectorXd supported_projections_;
  Eigen::VectorXd last_products_;
  // T1 is linear in the coefficients of Ã and g̃ (Eq. 22b). For the K coefficients seen to vary
  // at reset (~33 for the helicopter), T1 = e1 · basis_ · c, basis_ holding T1 for each unit
  // coefficient. Kept only while K < n(n+1)/2, where one product with basis_ is cheaper than
  // forming W1 and solving; otherwise K = 0.
  Eigen::MatrixXd basis_;
  ZeroPatternProduct first_term_product_;  // basis_ without its exact zeros (61 % for the helicopter)
  // Where a pass reads c: the column-major index in F of slots 0 … a_basis_count_ − 1, in B of the
  // others. 1 where an entry has no slot: there F, B must equal A0, g0 for T1 to be the product.
  std::vector<Eigen::Index> basis_entries_;
  Eigen::Index a_basis_count_ = 0;
  Eigen::MatrixXd a_unseen_, g_unseen_;
  Eigen::MatrixXd outside_input_rows_;  // n×m, 1 in the rows where B must be zero for input_rows
  // The paper's helicopter: its step runs on fixed-size views (ThetaDSettings::fixed_size).
  static constexpr int kFixedStates = 18;
  static constexpr int kFixedInputs = 5;
  bool fixed_size_ = false;             // evaluate_series<18, 5>, else <Dynamic, Dynamic>

  // Per-step buffers, sized in the constructor or at reset.
  Eigen::MatrixXd F_, B_;
  // The rows where this pass's B can be nonzero: input_rows_ when B has no nonzero outside them
  // (then g0 and g̃ have none either), else all n (every_row_). The products with g0 L⁻ᵀ and
  // g̃ L⁻ᵀ only read those rows (8 of the helicopter's 18).
  std::vector<Eigen::Index> every_row_;
  bool product_rows_are_input_rows_ = false;
  const std::vector<Eigen::Index>& product_rows() const {
    return product_rows_are_input_rows_ ? input_rows_ : every_row_;
  }
  // [g0 L⁻ᵀ, g̃ L⁻ᵀ] on those k rows, side by side (k × 2m), so that one product gives Y_i and Z_i
  // below; S2 = g̃s g̃sᵀ, S1 = g0s g̃sᵀ + g̃s g0sᵀ with g̃s the right half. Storage for up to
  // n × 2m entries, read as a contiguous k × 2m matrix.
  Eigen::MatrixXd compact_inputs_;
  Eigen::MatrixXd product_columns_;  // T_i on those k columns (n × k), the left factor
  // The nonzero coefficients of Ã = F − A0 (~33 of 324 for the helicopter): the first
  // a_tilde_count_ entries of arrays sized n² (sized, not reserved, so that copies keep them).
  std::vector<Eigen::Index> a_tilde_rows_, a_tilde_cols_;
  std::vector<double> a_tilde_values_;
  std::size_t a_tilde_count_ = 0;
  Eigen::VectorXd coefficients_;    // c of basis_
  // T1 = e1 · basis_ · c packed, and the c it was formed with (when T1 is not the last term):
  // within one control() x and t stay, so a later pass adds e1 · basis_ · Δc over the
  // coefficients that changed with the input instead of the whole product. first_term_current_:
  // the last pass formed T1 this way.
  Eigen::VectorXd first_term_, first_term_coefficients_;
  bool first_term_current_ = false;
  std::vector<Eigen::MatrixXd> T_;  // T_i (θ = 1, docs/model.md §8.1), already scaled by e_i
  std::vector<Eigen::MatrixXd> products_;  // [Y_i, Z_i] = T_i [g0 L⁻ᵀ, g̃ L⁻ᵀ] (n × 2m)
  std::vector<Eigen::MatrixXd> pairs_;     // C_i = Y_i + Z_{i−1}, i ≥ 1 (see form_right_side)
  Eigen::MatrixXd M_;                      // W_i = M + Mᵀ (docs/model.md §8.1)
  Eigen::MatrixXd left_, right_;           // the low-rank sums of M as one product left · rightᵀ
  Eigen::VectorXd packed_right_, packed_term_;
  Eigen::VectorXd v_, T0_v_, value_gradient_, Bt_gradient_, guess_, update_, applied_;
  int last_iterations_ = 0;
  double last_input_change_ = 0.0;
  // With settings_.certificates: T_{N−1} v (where B reads it), its part of u, R times a vector.
  Eigen::VectorXd last_term_gradient_, last_term_input_, weighted_input_;
  double last_term_ratio_ = 0.0;
};

}  // namespace thetad
