#pragma once

// The state-dependent Riccati equation controller (docs/model.md §8.2 step 1, Eq. 37): at every sample,
// P(x) solves P F(x) + F(x)ᵀ P − P B(x) R⁻¹ B(x)ᵀ P + Q = 0 and u = −R⁻¹ B(x)ᵀ P(x) v, with
// v = model.tracking_vector(measured, reference) (V_track of Eq. 36 for the helicopter).
//
// Generic over any SdcPlant. When the plant's F and B depend on the input (the helicopter's rotor
// speed follows T_mr), u is the fixed point of u -> F(x; u), B(x; u) -> u' of docs/model.md §6.2, started
// from the previously applied input: every pass solves one CARE.
//
// A step allocates nothing in any mode: Newton–Kleinman works in a NewtonKleinmanSolver (warm) or a
// CappedNewtonKleinman (capped) and the cold solve (the first sample, cold mode, a warm or capped
// step that failed) in a CareSolver, all sized at construction.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "controllers/sdre_certificates.hpp"
#include "core/capped_newton_kleinman.hpp"
#include "core/riccati.hpp"
#include "core/sdc_plant.hpp"

namespace thetad {

struct SdreSettings {
  enum class Mode {
    cold,  // CareSolver (matrix sign function, Laub–Schur fallback) at every pass, its stability
           // proved by the Lyapunov certificate when that holds
    warm,  // Newton–Kleinman from the last P (NewtonKleinmanSolver, its stability proved by the
           // Lyapunov certificate when that holds), the cold solve when that fails
    capped,  // exactly newton_iterations Newton–Kleinman steps from the last P (CappedNewtonKleinman:
             // a fixed cost per pass, what `thetad export` puts on a flight computer), the cold
             // solve when a step fails; the first sample starts from the cold solution at the
             // state reset() is given (the export's design point, docs/onboard.md)
  };
  Mode mode = Mode::warm;
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite (Eq. 37).
  Eigen::MatrixXd Q;
  Eigen::MatrixXd R;
  // The first guess of the fixed point at the first sample (the helicopter: T_mr = m g, docs/model.md §6.2).
  // Empty: zeros.
  Eigen::VectorXd initial_input;
  // Passes of the fixed point for input-dependent SDC plants; 1 is the one-step-lag variant.
  // Stops early when max|Δu| < fixed_point_tolerance.
  int fixed_point_iterations = 3;
  double fixed_point_tolerance = 1e-6;
  // Newton–Kleinman stopping rule of the warm mode (its normwise residual, newton_kleinman.hpp),
  // and its step limit.
  double newton_tolerance = 1e-12;
  int newton_max_iterations = 20;
  // The capped mode's steps per pass (1 … 20).
  int newton_iterations = 2;
  // Log the CARE's condition and forward-error estimates and the stabilizability margin of (F, B)
  // at every sample (SdreCertificates, docs/model.md §8.4): one more cold solve per step.
  bool certificates = false;
};

class SdreController final : public NamedController<"sdre"> {
 public:
  // Keeps a reference to the model: it must outlive the controller and its clones.
  // Throws thetad::Error on settings that do not fit the model.
  SdreController(const SdcPlant& model, SdreSettings settings);

  // "sdre-cold", "sdre-warm" or "sdre-capped": compare runs of the modes side by side.
  std::string name() const override;
  std::unique_ptr<Controller> clone() const override;

  // Forgets the last P and the counts; the first sample then solves cold in the cold and warm
  // modes. The capped mode solves cold here instead, at x0 with the initial input (throws
  // thetad::Error when that has no stabilizing solution), and starts from that P.
  void reset(const Eigen::VectorXd& x0, double t0) override;
  // Throws thetad::Error when the CARE fails at the first sample (no earlier P to fall back on).
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

  // P(x) of Eq. (37) with F(x; input), B(x; input), by a cold solve (independent of this
  // controller's history); t is unused (the SDRE is time-invariant) and kept for the same call
  // as ThetaDController::value_matrix, which the tuning compares it with (docs/model.md §8.2).
  // Throws thetad::Error when the CARE has no stabilizing solution at x.
  Eigen::MatrixXd value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double t) const;

  // Warm-mode passes whose Newton–Kleinman failed and were solved cold instead.
  int fallback_count() const { return fallback_count_; }
  // Passes at which every solver failed, so the last good P was used (the run continues).
  int failure_count() const { return failure_count_; }
  // Capped-mode samples whose last pass ended with ρ above 1e-12 (newton_kleinman.hpp).
  int unconverged_count() const { return unconverged_count_; }
  // {"care_newton_fallbacks", fallback_count()}, {"care_failures", failure_count()}, and in the
  // capped mode {"newton_unconverged", unconverged_count()}.
  std::vector<std::pair<std::string, double>> counters() const override;
  // In the capped mode newton_residual (ρ of the last pass's P; NaN when it was solved cold), then
  // SdreCertificates' columns when settings().certificates.
  std::vector<ControllerColumn> log_columns() const override;
  void log_values(std::vector<double>& row) const override;

  // P of the last pass of the last control() (the last good one after a failure).
  const Eigen::MatrixXd& last_value_matrix() const { return P_; }
  // Fixed-point passes of the last control() and the max|Δu| of its last pass.
  int last_iterations() const override { return last_iterations_; }
  double last_input_change() const { return last_input_change_; }
  const SdreSettings& settings() const { return settings_; }

 private:
  // Solves the CARE for F_, B_ into P_ by the mode's rule; counts fallbacks and failures.
  void update_value_matrix(double t);

  const SdcPlant* model_;
  SdreSettings settings_;
  Eigen::MatrixXd R_inverse_;
  std::optional<NewtonKleinmanSolver> newton_;  // the warm mode's, set in the constructor
  std::optional<CappedNewtonKleinman> capped_;  // the capped mode's
  std::optional<CareSolver> cold_;              // both modes', set in the constructor
  std::optional<SdreCertificates> certificates_;  // with settings_.certificates

  // Per-step buffers, sized in the constructor.
  Eigen::MatrixXd F_, B_, P_;
  bool have_P_ = false;
  Eigen::VectorXd v_, Pv_, BtPv_, guess_, update_, applied_;
  int fallback_count_ = 0;
  int failure_count_ = 0;
  int unconverged_count_ = 0;
  double newton_residual_ = 0.0;  // ρ of the last pass (capped mode)
  int last_iterations_ = 0;
  double last_input_change_ = 0.0;
};

}  // namespace thetad
