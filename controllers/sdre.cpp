#include "controllers/sdre.hpp"

#include <limits>

#include <Eigen/Cholesky>

#include "controllers/feedforward_controller.hpp"
#include "controllers/matrix_setting.hpp"
#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "core/error.hpp"

namespace thetad {

namespace {

// ρ above which a capped-mode sample counts as not converged: the warm mode's tolerance.
constexpr double kNewtonConverged = 1e-12;

}  // namespace

SdreController::SdreController(const SdcPlant& model, SdreSettings settings)
    : model_(&model), settings_(std::move(settings)) {
  const Eigen::Index n = model.state_dim(), m = model.input_dim();
  if (settings_.fixed_point_iterations < 1) {
    throw Error("sdre: fixed_point_iterations must be >= 1, got " + std::to_string(settings_.fixed_point_iterations));
  }
  if (!(settings_.fixed_point_tolerance >= 0.0)) throw Error("sdre: fixed_point_tolerance must be >= 0");
  if (settings_.newton_iterations < 1 || settings_.newton_iterations > 20) {
    throw Error("sdre: newton_iterations must be in [1, 20], got " + std::to_string(settings_.newton_iterations));
  }
  require_matrix_shape("sdre", "Q", settings_.Q, n, n);
  require_matrix_shape("sdre", "R", settings_.R, m, m);
  if (settings_.initial_input.size() == 0) settings_.initial_input = Eigen::VectorXd::Zero(m);
  require_matrix_shape("sdre", "initial_input", settings_.initial_input, m, 1);
  // Q and R are checked in full by every CARE solve; R⁻¹ is needed here for u = −R⁻¹BᵀPv even
  // when a solve fails, so R's definiteness is checked once, now.
  const Eigen::LLT<Eigen::MatrixXd> llt(settings_.R);
  if (llt.info() != Eigen::Success || !settings_.R.isApprox(settings_.R.transpose())) {
    throw Error("sdre: R must be symmetric positive definite");
  }
  R_inverse_ = llt.solve(Eigen::MatrixXd::Identity(m, m));
  // Both steps need P, not the closed-loop eigenvalues: the Lyapunov certificate spares the warm
  // one a Schur form and the cold one an eigensolver whenever it holds.
  if (settings_.mode == SdreSettings::Mode::warm) {
    newton_.emplace(settings_.Q, settings_.R, settings_.newton_tolerance, settings_.newton_max_iterations,
                    StabilityProof::lyapunov);
  }
  if (settings_.mode == SdreSettings::Mode::capped) capped_.emplace(settings_.Q, settings_.R, settings_.newton_iterations);
  cold_.emplace(settings_.Q, settings_.R, CareMethod::automatic, StabilityProof::lyapunov);
  if (settings_.certificates) certificates_.emplace(settings_.Q, settings_.R);

  F_.setZero(n, n);
  B_.setZero(n, m);
  P_.setZero(n, n);
  v_.setZero(n);
  Pv_.setZero(n);
  BtPv_.setZero(m);
  guess_ = settings_.initial_input;
  update_.setZero(m);
  applied_ = settings_.initial_input;
}

std::string SdreController::name() const {
  switch (settings_.mode) {
    case SdreSettings::Mode::cold: return kName + std::string("-cold");
    case SdreSettings::Mode::warm: return kName + std::string("-warm");
    case SdreSettings::Mode::capped: return kName + std::string("-capped");
  }
  return kName;
}

std::unique_ptr<Controller> SdreController::clone() const { return std::make_unique<SdreController>(*this); }

void SdreController::reset(const Eigen::VectorXd& x0, double) {
  if (x0.size() != model_->state_dim()) {
    throw Error("sdre: initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(model_->state_dim()));
  }
  applied_ = settings_.initial_input;
  have_P_ = false;
  if (newton_) newton_->forget();
  fallback_count_ = 0;
  failure_count_ = 0;
  unconverged_count_ = 0;
  newton_residual_ = 0.0;
  last_iterations_ = 0;
  last_input_change_ = 0.0;
  if (capped_) {
    // The first sample starts from the design point's P, as the exported step does (it stores
    // this P): K Newton steps from it at every sample, the first included, whatever the first
    // measured state is.
    model_->sdc(x0, applied_, F_, B_);
    try {
      P_ = cold_->solve(F_, B_).P;
    } catch (const Error& error) {
      throw Error(std::string("sdre: no stabilizing CARE solution at the initial state: ") + error.what());
    }
    have_P_ = true;
  }
}

void SdreController::update_value_matrix(double t) {
  try {
    if (settings_.mode == SdreSettings::Mode::warm && have_P_) {
      try {
        P_ = newton_->solve(F_, B_, P_).P;
        return;
      } catch (const Error&) {
        // The last P does not stabilize (F, B) here, or Newton did not converge: solve cold.
        ++fallback_count_;
      }
    }
    if (settings_.mode == SdreSettings::Mode::capped && have_P_) {
      try {
        P_ = capped_->solve(F_, B_, P_);
        newton_residual_ = capped_->last_residual_to_terms();
        return;
      } catch (const Error&) {
        ++fallback_count_;  // a step failed here (a closed loop not Hurwitz, a singular operator): solve cold
      }
    }
    newton_residual_ = std::numeric_limits<double>::quiet_NaN();
    P_ = cold_->solve(F_, B_).P;
    have_P_ = true;
  } catch (const Error& error) {
    if (!have_P_) {
      throw Error("sdre: no stabilizing CARE solution at t = " + std::to_string(t) +
                  " s and no earlier one to fall back on: " + error.what());
    }
    // Keep flying on the last good P (counted, reported by counters()) rather than end the run on
    // one state where (F, B) is momentarily not stabilizable.
    ++failure_count_;
  }
}

void SdreController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                             const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  model_->tracking_vector(measured_state, reference, v_);
  // docs/model.md §6.2: start from the previously applied input; without input dependence one pass is exact.
  const int passes = model_->sdc_depends_on_input() ? settings_.fixed_point_iterations : 1;
  guess_ = applied_;
  last_iterations_ = 0;
  do {
    model_->sdc(measured_state, guess_, F_, B_);
    update_value_matrix(t);
    Pv_.noalias() = P_ * v_;
    BtPv_.noalias() = B_.transpose() * Pv_;
    update_.noalias() = -R_inverse_ * BtPv_;  // Eq. (35) with P(x) in place of ΣT_i
    last_input_change_ = (update_ - guess_).cwiseAbs().maxCoeff();
    guess_ = update_;
    ++last_iterations_;
  } while (last_iterations_ < passes && last_input_change_ >= settings_.fixed_point_tolerance);
  applied_ = guess_;
  u = applied_;
  if (capped_ && newton_residual_ > kNewtonConverged) ++unconverged_count_;
  // At the F, B the last pass solved with (docs/model.md §8.4).
  if (certificates_) certificates_->evaluate(F_, B_);
}

Eigen::MatrixXd SdreController::value_matrix(const Eigen::VectorXd& x, const Eigen::VectorXd& input, double) const {
  const SdcPlant::Coefficients sdc = model_->sdc(x, input);
  return solve_care(sdc.F, sdc.B, settings_.Q, settings_.R).P;
}

std::vector<std::pair<std::string, double>> SdreController::counters() const {
  std::vector<std::pair<std::string, double>> counters{{"care_newton_fallbacks", fallback_count_},
                                                       {"care_failures", failure_count_}};
  if (capped_) counters.emplace_back("newton_unconverged", unconverged_count_);
  return counters;
}

std::vector<ControllerColumn> SdreController::log_columns() const {
  std::vector<ControllerColumn> columns;
  if (capped_) columns.push_back({{"newton_residual", ""}, ControllerColumn::Worst::largest});
  if (certificates_) {
    for (ControllerColumn& column : SdreCertificates::columns()) columns.push_back(std::move(column));
  }
  return columns;
}

void SdreController::log_values(std::vector<double>& row) const {
  if (capped_) row.push_back(newton_residual_);
  if (certificates_) certificates_->values(row);
}

namespace {

std::unique_ptr<Controller> make_sdre(const Settings& fields, const ControllerContext& context) {
  fields.allow_only({"mode", "newton_iterations", "fixed_point_iterations", "Q", "R", "feedforward", "certificates"});
  SdreSettings settings;
  const std::string mode = fields.choice("mode", "warm", {"cold", "warm", "capped"});
  settings.mode = mode == "warm" ? SdreSettings::Mode::warm
                  : mode == "cold" ? SdreSettings::Mode::cold
                                   : SdreSettings::Mode::capped;
  // Newton steps per pass of the capped mode (read in every mode, so that the settings as used
  // rebuild the controller; only the capped mode uses them): a fixed cost per pass.
  settings.newton_iterations = fields.integer("newton_iterations", settings.newton_iterations, 1, 20);
  // Bounded: every pass is a Riccati solve within the 1 ms step; the fixed point settles in 2-3.
  settings.fixed_point_iterations = fields.integer("fixed_point_iterations", settings.fixed_point_iterations, 1, 100);
  // The context's design defaults: for the helicopter the paper's weights, and the fixed point
  // starts from hover thrust at the first sample (docs/model.md §6.2).
  const DesignDefaults& defaults = context.defaults;
  settings.Q = fields.diagonal_weight("Q", defaults.state_weights, Settings::Weight::positive_semidefinite);
  settings.R = fields.diagonal_weight("R", defaults.input_weights, Settings::Weight::positive_definite);
  settings.certificates = fields.boolean("certificates", false);
  const FeedForward feedforward = read_feedforward(fields, FeedForward::none);
  // With the trim's input applied, the decision variable v = u − u_r starts from 0.
  settings.initial_input =
      feedforward == FeedForward::velocity_trim ? Eigen::VectorXd::Zero(defaults.input.size()) : defaults.input;
  if (context.settings_only) return nullptr;
  if (feedforward == FeedForward::none) return std::make_unique<SdreController>(context.plant, std::move(settings));
  return std::make_unique<FeedForwardController>(
      error_form_of(context, feedforward, zero_design_point(context.plant)),
      [settings](const SdcPlant& error_form) { return std::make_unique<SdreController>(error_form, settings); });
}

const ControllerRegistration sdre_registration = register_controller<SdreController>(
    "state-dependent Riccati equation, one CARE per sample (Eq. 37); settings: mode (cold|warm|capped), "
            "newton_iterations (capped: Newton steps per pass, 1-20, default 2), "
            "fixed_point_iterations, Q, R, feedforward (none|velocity|velocity+trim), certificates (off|on)",
    make_sdre);

}  // namespace

}  // namespace thetad
