#include "controllers/lqr.hpp"

#include <string>
#include <utility>

#include "controllers/feedforward_controller.hpp"
#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "core/error.hpp"
#include "core/trim.hpp"

namespace thetad {

namespace {

Eigen::Index checked_design_states(const SdcPlant& model, const OperatingPoint& point, const LqrSettings& settings) {
  const Eigen::Index n = model.state_dim(), m = model.input_dim();
  if (point.state.size() != n || point.tracking.size() != n || point.input.size() != m) {
    throw Error("lqr: the operating point's state, tracking vector and input have " +
                std::to_string(point.state.size()) + ", " + std::to_string(point.tracking.size()) + " and " +
                std::to_string(point.input.size()) + " entries, the model needs " + std::to_string(n) + ", " +
                std::to_string(n) + " and " + std::to_string(m));
  }
  return settings.design_states == 0 ? n : settings.design_states;
}

}  // namespace

LqrController::LqrController(const SdcPlant& model, OperatingPoint point, LqrSettings settings)
    : model_(&model),
      point_(std::move(point)),
      design_states_(checked_design_states(model, point_, settings)),
      v_(Eigen::VectorXd::Zero(model.state_dim())) {
  design_ = design_lqr(model, point_, settings.Q, settings.R, design_states_);
}

LqrController::LqrController(const SdcPlant& model, OperatingPoint point, CareResult design,
                             Eigen::Index design_states)
    : model_(&model),
      point_(std::move(point)),
      design_(std::move(design)),
      design_states_(design_states),
      v_(Eigen::VectorXd::Zero(model.state_dim())) {
  checked_design_states(model, point_, LqrSettings{{}, {}, design_states});
  if (design_.K.rows() != model.input_dim() || design_.K.cols() != design_states_)
    throw Error("lqr: the gain is " + std::to_string(design_.K.rows()) + "x" + std::to_string(design_.K.cols()) +
                ", the model needs " + std::to_string(model.input_dim()) + "x" + std::to_string(design_states_));
}

void LqrController::reset(const Eigen::VectorXd& x0, double) {
  if (x0.size() != model_->state_dim()) {
    throw Error("lqr: initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(model_->state_dim()));
  }
}

void LqrController::control(double, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                            const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  model_->tracking_vector(measured_state, reference, v_);
  v_.head(design_states_) -= point_.tracking.head(design_states_);
  u = point_.input;
  u.noalias() -= design_.K * v_.head(design_states_);
}

namespace {

// Another plant than the helicopter: one gain at its design point, the origin it is regulated to
// with its design input u0 (SdcPlant::design_defaults), which must be an equilibrium there.
std::unique_ptr<Controller> make_design_point_lqr(const Settings& fields, const ControllerContext& context) {
  const SdcPlant& plant = context.plant;
  fields.allow_only({"Q", "R"});
  LqrSettings settings;
  settings.Q = fields.diagonal_weight("Q", context.defaults.state_weights, Settings::Weight::positive_semidefinite);
  settings.R = fields.diagonal_weight("R", context.defaults.input_weights, Settings::Weight::positive_definite);
  if (context.settings_only) return nullptr;
  const Eigen::VectorXd origin = Eigen::VectorXd::Zero(plant.state_dim());
  const double drift = plant.f(origin, context.defaults.input).cwiseAbs().maxCoeff();
  if (!(drift <= 1e-9))
    throw Error("lqr: the plant's design point (the origin with its design input u0) is no equilibrium, "
                "max |f(0, u0)| = " + std::to_string(drift) + ": a gain designed there would not hold it");
  Eigen::VectorXd tracking(plant.state_dim());
  plant.tracking_vector(origin, Reference{}, tracking);
  return std::make_unique<LqrController>(plant, OperatingPoint{origin, context.defaults.input, tracking},
                                         std::move(settings));
}

std::unique_ptr<Controller> make_lqr(const Settings& fields, const ControllerContext& context) {
  if (dynamic_cast<const heli::Helicopter*>(&context.plant) == nullptr) return make_design_point_lqr(fields, context);
  const heli::Helicopter& model = helicopter_of(context, "lqr");
  fields.allow_only({"Q", "R", "feedforward"});
  LqrSettings settings;
  settings.Q = fields.diagonal_weight("Q", context.defaults.state_weights, Settings::Weight::positive_semidefinite);
  settings.R = fields.diagonal_weight("R", context.defaults.input_weights, Settings::Weight::positive_definite);
  settings.design_states = heli::kStateDim - 1;  // all but the bias state s
  const FeedForward feedforward = read_feedforward(fields, FeedForward::none);
  if (context.settings_only) return nullptr;
  const Eigen::VectorXd& x0 = context.initial_state;
  if (x0.size() != heli::kStateDim) {
    throw Error("lqr: initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(heli::kStateDim));
  }
  const Trim trim = find_trim(model, TrimCondition::hover(-x0(heli::kZp), x0(heli::kPsi)));
  if (feedforward == FeedForward::none)
    return std::make_unique<LqrController>(model, operating_point(model, trim), std::move(settings));
  // The gain of the hover design, flown on the error form around the hover trim (velocity) or
  // around the trim of the commanded velocity (velocity+trim): u = u_r − K e.
  const OperatingPoint hover = operating_point(model, trim);
  const CareResult design = design_lqr(model, hover, settings.Q, settings.R, settings.design_states);
  const Eigen::Index n = model.state_dim(), m = model.input_dim(), design_states = settings.design_states;
  const OperatingPoint on_error{hover.state, Eigen::VectorXd::Zero(m), Eigen::VectorXd::Zero(n)};
  return std::make_unique<FeedForwardController>(
      error_form_of(context, feedforward, TrimPoint{trim.state, trim.input, Eigen::VectorXd::Zero(n)}),
      [on_error, design, design_states](const SdcPlant& error_form) {
        return std::make_unique<LqrController>(error_form, on_error, design, design_states);
      });
}

const ControllerRegistration lqr_registration = register_controller<LqrController>(
    "LQR at the hover trim, one fixed gain on V_track (Eq. 36) with the paper's Q and R; settings: Q, R, "
    "feedforward (none|velocity|velocity+trim); on another plant, at its design point (the origin, its u0)",
    make_lqr);

}  // namespace

}  // namespace thetad
