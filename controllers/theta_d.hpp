#pragma once

// The θ–D controller (paper-spec §5, §7): a series approximation Σ_{i<N} T_i(x, t) of the SDRE
// solution P(x) around the frozen system (A0, g0) = (F, B) at the initial state. T0 solves one
// CARE at reset; every further term solves a Lyapunov equation with the same constant operator
// L(T) = T Ac0 + Ac0ᵀ T, so one control step is a few products and N − 1 packed linear maps.
//
// Generic over any SdcPlant: it never knows which plant it flies.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "core/lyapunov.hpp"
#include "core/sdc_plant.hpp"

namespace thetad {

struct ThetaDSettings {
  // N: the series T0 + T1 + … + T_{N−1} (spec §5.8: the paper uses N = 3). N ≥ 1.
  int terms = 3;
  // k_i, l_i of e_i(t) = 1 − k_i exp(−l_i (t − t0)) for i = 1 … N−1 (Eq. 25). Empty: all 1
  // (spec §7.4). k = 0 gives e_i ≡ 1, the plain series.
  Eigen::VectorXd k;
  Eigen::VectorXd l;
  // Weights of Eq. (14): Q n×n symmetric positive semi-definite, R m×m symmetric positive definite.
  Eigen::MatrixXd Q;
  Eigen::MatrixXd R;
  // u0, the input at which the initial SDC F(x0; u0), B(x0; u0) is evaluated, and the first guess
  // of the fixed point (spec §7.1, §7.6). Empty: zeros.
  Eigen::VectorXd initial_input;
  // Passes of the fixed point u -> F(x; u), B(x; u) -> u' for plants whose SDC depends on the
  // input (spec §7.6); 1 is the one-step-lag variant. Stops early when max|Δu| < tolerance.
  int fixed_point_iterations = 3;
  double fixed_point_tolerance = 1e-6;
};

class ThetaDController final : public Controller {
 public:
  // Keeps a reference to the model: it must outlive the controller and its clones.
  // Throws thetad::Error on settings that do not fit the model.
  ThetaDController(const SdcPlant& model, ThetaDSettings settings);

  std::string name() const override { return "theta-d"; }
  std::unique_ptr<Controller> clone() const override;

  // Offline part of spec §5.10: A0, g0 at (x0; u0), T0 from (22a), Ac0 and its Lyapunov solver.
  // Throws thetad::Error when the CARE has no stabilizing solution at x0.
  void reset(const Eigen::VectorXd& x0, double t0) override;
  // Eq. (35) with the fixed point of spec §7.6. Allocates nothing.
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const sim::Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

  // Σ_{i<N} T_i(x, t) with F(x; input), B(x; input): the θ–D approximation of the SDRE's P(x),
  // by the same code as one pass of control(). terms() then holds the individual T_i.
  Eigen::MatrixXd value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t);

  // Diagnostics (valid after reset()).
  const std::vector<Eigen::MatrixXd>& terms() const { return T_; }  // T_0 … T_{N−1} of the last evaluation
  const Eigen::MatrixXd& T0() const { return T_[0]; }
  const Eigen::MatrixXd& A0() const { return A0_; }
  const Eigen::MatrixXd& g0() const { return g0_; }
  const Eigen::MatrixXd& Ac0() const { return Ac0_; }
  const Eigen::VectorXcd& closed_loop_eigenvalues() const { return Ac0_eigenvalues_; }
  // Fixed-point passes of the last control() and the max|Δu| of its last pass.
  int last_iterations() const { return last_iterations_; }
  double last_input_change() const { return last_input_change_; }
  const ThetaDSettings& settings() const { return settings_; }

 private:
  void require_reset(const char* caller) const;
  // One pass of spec §5.10 steps 1–2 at (x; input), time t: fills F_, B_ and T_[1 … N−1].
  void evaluate_series(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& input,
                       double t);

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

  // Per-step buffers, sized in the constructor.
  Eigen::MatrixXd F_, B_;
  Eigen::MatrixXd g_tilde_scaled_;  // g̃ L⁻ᵀ: S2 = g̃s g̃sᵀ, S1 = g0s g̃sᵀ + g̃s g0sᵀ
  // The nonzero coefficients of Ã = F − A0 (~33 of 324 for the helicopter): the first
  // a_tilde_count_ entries of arrays sized n² (sized, not reserved, so that copies keep them).
  std::vector<Eigen::Index> a_tilde_rows_, a_tilde_cols_;
  std::vector<double> a_tilde_values_;
  std::size_t a_tilde_count_ = 0;
  std::vector<Eigen::MatrixXd> T_;  // T_i (θ = 1, spec §5.7), already scaled by e_i
  std::vector<Eigen::MatrixXd> Y_;  // T_i g0 L⁻ᵀ
  std::vector<Eigen::MatrixXd> Z_;  // T_i g̃ L⁻ᵀ
  Eigen::MatrixXd M_, W_;           // W_i = M + Mᵀ (spec §5.4)
  Eigen::VectorXd v_, value_gradient_, Bt_gradient_, guess_, update_, applied_;
  int last_iterations_ = 0;
  double last_input_change_ = 0.0;
};

}  // namespace thetad
