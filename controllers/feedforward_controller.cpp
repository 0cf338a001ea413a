#include "controllers/feedforward_controller.hpp"

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "settings/settings.hpp"

namespace thetad {

FeedForwardController::FeedForwardController(ErrorFormPlant error_form, Build build)
    : error_form_(std::make_unique<ErrorFormPlant>(std::move(error_form))),
      build_(std::move(build)),
      inner_(build_(*error_form_)) {
  if (!inner_) throw Error("feed-forward: the inner controller was not built");
}

std::unique_ptr<Controller> FeedForwardController::clone() const {
  return std::make_unique<FeedForwardController>(*error_form_, build_);
}

void FeedForwardController::reset(const Eigen::VectorXd& x0, double t0) {
  const SdcPlant& plant = error_form_->plant();
  if (x0.size() != plant.state_dim())
    throw Error(inner_->name() + ": initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(plant.state_dim()));
  Reference holding;
  holding.position = plant.tracked_position(x0);
  error_form_->aim(x0, holding);
  inner_->reset(x0, t0);
}

void FeedForwardController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                                    const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  error_form_->aim(measured_state, reference);
  inner_->control(t, measured_state, reference, u);
  u += error_form_->motion().input;
}

FeedForward read_feedforward(const Settings& fields, FeedForward fallback) {
  return parse_feedforward(fields.choice("feedforward", feedforward_name(fallback),
                                         {kFeedForwardChoices[0], kFeedForwardChoices[1], kFeedForwardChoices[2]}));
}

ErrorFormPlant error_form_of(const ControllerContext& context, FeedForward feedforward, TrimPoint design) {
  return ErrorFormPlant(context.plant, feedforward, std::move(design),
                        feedforward == FeedForward::velocity_trim ? context.trims() : nullptr);
}

TrimPoint zero_design_point(const SdcPlant& plant) {
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  return {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(m), Eigen::VectorXd::Zero(n)};
}

}  // namespace thetad
