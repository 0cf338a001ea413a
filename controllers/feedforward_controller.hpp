#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "controllers/controller.hpp"
#include "core/error.hpp"
#include "core/error_form_plant.hpp"

namespace thetad {

class Settings;
struct ControllerContext;

// A built-in controller flying with feed-forward (docs/model.md §7.1): the inner controller is
// designed on the plant's error form (ErrorFormPlant), which this controller aims at the reference
// before every step; the inner one computes the decision variable v, and u = u_r + v is applied.
// With feedforward none a controller is built on the plant itself, without this wrapper.
class FeedForwardController final : public Controller {
 public:
  // Builds the inner controller on the given error form: called once here and once per clone,
  // since the inner controller keeps the address of its own error form.
  using Build = std::function<std::unique_ptr<Controller>(const SdcPlant& error_form)>;

  FeedForwardController(ErrorFormPlant error_form, Build build);

  std::string name() const override { return inner_->name(); }
  std::unique_ptr<Controller> clone() const override;
  // The inner reset() at a motion that holds x0 at rest (its tracked positions commanded, no
  // velocity): θ–D's frozen pair (A0, g0) is taken there.
  void reset(const Eigen::VectorXd& x0, double t0) override;
  // Allocates nothing beyond what the inner step does.
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;
  std::vector<std::pair<std::string, double>> counters() const override { return inner_->counters(); }
  // The inner controller's, of its decision variable v (docs/model.md §8.4).
  std::vector<ControllerColumn> log_columns() const override { return inner_->log_columns(); }
  void log_values(std::vector<double>& row) const override { inner_->log_values(row); }
  int last_iterations() const override { return inner_->last_iterations(); }

  const Controller& inner() const { return *inner_; }
  const ErrorFormPlant& error_form() const { return *error_form_; }

 private:
  std::unique_ptr<ErrorFormPlant> error_form_;  // on the heap: the inner controller keeps its address
  Build build_;
  std::unique_ptr<Controller> inner_;
};

// `controller` as the controller type C it was built as, for a tool that reads its value matrix in
// the paper's form (thetad tune's σ fit, thetad approximation). Throws thetad::Error naming `tool`
// when it flies with feed-forward (its value matrix is then of the error form) or is no C.
template <class C>
C& paper_form(Controller& controller, const std::string& tool) {
  if (dynamic_cast<const FeedForwardController*>(&controller))
    throw Error(tool + " compares value matrices in the paper's form: " + controller.name() +
                " flies with feed-forward here; set its feedforward to none");
  if (auto* found = dynamic_cast<C*>(&controller)) return *found;
  throw Error(tool + ": " + controller.name() + " is not the controller it needs");
}

// The `feedforward` field of a built-in controller's settings (none, velocity, velocity+trim).
FeedForward read_feedforward(const Settings& fields, FeedForward fallback);

// The error form a controller with `feedforward` (not none) flies: around `design` (its own
// design point), with the context's shared trims for velocity+trim.
ErrorFormPlant error_form_of(const ControllerContext& context, FeedForward feedforward, TrimPoint design);

// A design point of zeros (state, input, rate): θ–D's and the SDRE's, whose tracking vector
// regulates to zero and whose input carries its own trim.
TrimPoint zero_design_point(const SdcPlant& plant);

}  // namespace thetad
