#include "core/error_form_plant.hpp"

#include <string>
#include <utility>

#include "core/error.hpp"

namespace thetad {

ErrorFormPlant::ErrorFormPlant(const SdcPlant& plant, FeedForward feedforward, TrimPoint design,
                               std::shared_ptr<const TrimSource> trims)
    : plant_(&plant),
      feedforward_(feedforward),
      design_(std::move(design)),
      trims_(std::move(trims)),
      bias_(plant.bias_state()) {
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  if (feedforward_ == FeedForward::none) throw Error("feed-forward none flies the plant itself, not its error form");
  if (bias_ < 0 || bias_ >= n)
    throw Error("feedforward " + feedforward_name(feedforward_) +
                ": this plant has no bias state to carry the reference and trim terms (SdcPlant::bias_state); it "
                "flies feedforward none only");
  if (feedforward_ == FeedForward::velocity_trim && !trims_)
    throw Error("feedforward velocity+trim: this plant has no trims (SdcPlant::trim_source)");
  if (design_.state.size() != n || design_.rate.size() != n || design_.input.size() != m)
    throw Error("feed-forward: the design point has " + std::to_string(design_.state.size()) + " states, " +
                std::to_string(design_.rate.size()) + " rates and " + std::to_string(design_.input.size()) +
                " inputs, the plant needs " + std::to_string(n) + ", " + std::to_string(n) + " and " +
                std::to_string(m));
  motion_ = design_;
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(n, n), B = Eigen::MatrixXd::Zero(n, m);
  plant.sdc_constant(F, B);
  constant_column_ = F.col(bias_);
  input_.setZero(m);
  terms_.setZero(n);
}

void ErrorFormPlant::aim(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference) {
  if (feedforward_ == FeedForward::velocity_trim) {
    trims_->trim(reference, motion_);
  } else {
    motion_.state = design_.state;
    motion_.input = design_.input;
    motion_.rate = design_.rate;
  }
  plant_->commanded_motion(measured, reference, motion_);
  motion_.state[bias_] = 0.0;
  motion_.rate[bias_] = 0.0;
}

void ErrorFormPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
                       Eigen::Ref<Eigen::VectorXd> xdot) const {
  input_ = motion_.input + v;
  plant_->f(x, input_, xdot);
  xdot -= motion_.rate;
}

void ErrorFormPlant::tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference&,
                                     Eigen::Ref<Eigen::VectorXd> e) const {
  e = measured - motion_.state;
  e[bias_] = 1.0;
}

void ErrorFormPlant::add_reference_terms(Eigen::Ref<Eigen::MatrixXd> F,
                                         const Eigen::Ref<const Eigen::MatrixXd>& B) const {
  terms_.noalias() = F * motion_.state;
  terms_.noalias() += B * motion_.input;
  terms_ -= motion_.rate;
  F.col(bias_) += terms_;
}

void ErrorFormPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
                         Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  input_ = motion_.input + v;
  plant_->sdc(x, input_, F, B);
  add_reference_terms(F, B);
}

void ErrorFormPlant::sdc_constant(Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  plant_->sdc_constant(F, B);
}

void ErrorFormPlant::sdc_varying(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
                                 Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  F.col(bias_) = constant_column_;
  input_ = motion_.input + v;
  plant_->sdc_varying(x, input_, F, B);
  add_reference_terms(F, B);
}

DesignDefaults ErrorFormPlant::design_defaults() const {
  DesignDefaults defaults = plant_->design_defaults();
  if (feedforward_ == FeedForward::velocity_trim) defaults.input.setZero();
  return defaults;
}

}  // namespace thetad
