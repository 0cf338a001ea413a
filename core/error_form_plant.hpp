#pragma once

#include <memory>

#include <Eigen/Core>

#include "core/feedforward.hpp"
#include "core/sdc_plant.hpp"

namespace thetad {

// A plant as a controller with feed-forward sees it (docs/model.md §7.1). At each sample aim() sets
// the commanded motion: the state x_r and input u_r the plant holds while it flies the reference
// (the trim at the commanded velocity for velocity+trim; the controller's own design point for
// velocity) with the commanded position, velocity and integrals written in, and x_r's rate ẋ_r.
// The controller then acts on the error e = x − x_r (the bias state kept at 1) with the decision
// variable v = u − u_r, and the error dynamics keep an exact SDC form:
//
//   ė = f(x, u_r + v) − ẋ_r = F_e(x) e + B(x; u_r + v) v,   F_e = F(x; u) + c 1_sᵀ,
//   c = F(x; u) x_r + B(x; u) u_r − ẋ_r   (x_r's bias entry 0, so F's s column does not enter c),
//
// the reference and trim terms entering the bias column, as the gravity does in F. Exact for the
// measured state (the only approximation left is the trims' blend: ẋ_r of a trim entry is the
// blend's rate along the commanded acceleration, core/trim_table.hpp).
//
// Stateful (the aimed motion): one per controller, which aims it before every control step.
class ErrorFormPlant final : public SdcPlant {
 public:
  // `design`: the motion the controller regulates to where the reference says nothing (its
  // state, input and rate; sized n, m, n): zeros for θ–D and the SDRE, the hover trim for the LQR.
  // `trims` (velocity+trim) must be given. Throws thetad::Error when the plant has no bias state
  // or `feedforward` is none (that is the plant itself) or sizes do not fit.
  ErrorFormPlant(const SdcPlant& plant, FeedForward feedforward, TrimPoint design,
                 std::shared_ptr<const TrimSource> trims);

  // The motion of this sample. Allocates nothing.
  void aim(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference);
  const TrimPoint& motion() const { return motion_; }
  FeedForward feedforward() const { return feedforward_; }
  const SdcPlant& plant() const { return *plant_; }
  const std::shared_ptr<const TrimSource>& trims() const { return trims_; }

  int state_dim() const override { return plant_->state_dim(); }
  int input_dim() const override { return plant_->input_dim(); }
  bool sdc_depends_on_input() const override { return plant_->sdc_depends_on_input(); }
  int bias_state() const override { return bias_; }
  // ė for the decision variable v: f(x, u_r + v) − ẋ_r.
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  // e = measured − x_r with the bias entry 1 (the reference was taken by aim()).
  void tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                       Eigen::Ref<Eigen::VectorXd> e) const override;
  // F_e and B at (x; u_r + v).
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  void sdc_constant(Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  void sdc_varying(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v,
                   Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  // The plant's, with the decision variable starting at 0 when the trim holds the plant.
  DesignDefaults design_defaults() const override;

 private:
  // F's bias column += c, from F and B at the input they were evaluated at.
  void add_reference_terms(Eigen::Ref<Eigen::MatrixXd> F, const Eigen::Ref<const Eigen::MatrixXd>& B) const;

  const SdcPlant* plant_;
  FeedForward feedforward_;
  TrimPoint design_;
  std::shared_ptr<const TrimSource> trims_;
  int bias_;
  TrimPoint motion_;
  // The bias column as the plant's sdc_constant() leaves it: sdc_varying() restores it before the
  // plant writes its varying entries, so c is added once to a fresh column.
  Eigen::VectorXd constant_column_;
  mutable Eigen::VectorXd input_, terms_;  // u_r + v and c: buffers of the const evaluations
};

}  // namespace thetad
