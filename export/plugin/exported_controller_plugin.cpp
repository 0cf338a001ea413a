// A plug-in that flies a header `thetad export` wrote (docs/onboard.md, "Fly it"): its step in double
// and in float, registered as the controllers LABEL-exported and LABEL-float, so that `thetad
// compare` flies them on the same seed as the library's controller and pairs their J, errors and
// completion. Built by thetad_add_exported_plugin() (cmake/thetadPlugin.cmake), which defines
// THETAD_EXPORTED_HEADER (the header's path, quoted) and THETAD_EXPORTED_NAMESPACE (its namespace).
//
// The exported design is fixed: it flies correctly only from the initial state and with the model
// options of the scenario it was exported at. The float controller gets the flight's double
// measurements rounded to float and gives its float u back as double: the float step is what
// is tested, not float sensors.
#include THETAD_EXPORTED_HEADER

#include <memory>
#include <string>

#include "controllers/registry.hpp"
#include "core/error.hpp"

namespace {

namespace exported = THETAD_EXPORTED_NAMESPACE;
using thetad_onboard::kInputs;
using thetad_onboard::kStates;

template <class T>
class ExportedController final : public thetad::Controller {
 public:
  explicit ExportedController(std::string name) : name_(std::move(name)), state_(std::make_unique<State>()) {}
  // The state (up to tens of KiB) lives on the heap, allocated here and never on the hot path.
  ExportedController(const ExportedController& other)
      : name_(other.name_), state_(std::make_unique<State>(*other.state_)) {}

  std::string name() const override { return name_; }
  void reset(const Eigen::VectorXd&, double) override { exported::reset(*state_); }

  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const thetad::Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override {
    T measured[kStates], input[kInputs];
    for (int i = 0; i < kStates; ++i) measured[i] = T(measured_state[i]);
    thetad_onboard::Reference<T> command;
    for (int i = 0; i < 3; ++i) {
      command.position[i] = T(reference.position[i]);
      command.integral[i] = T(reference.integral[i]);
      command.velocity[i] = T(reference.velocity[i]);
      command.acceleration[i] = T(reference.acceleration[i]);
    }
    const thetad_onboard::Status status = exported::step(*state_, T(t), measured, command, input);
    if (status != thetad_onboard::Status::ok)
      throw thetad::Error(name_ + ": the exported step failed at t = " + std::to_string(t) + " s: " +
                          thetad_onboard::status_name(status));
    for (int k = 0; k < kInputs; ++k) u[k] = double(input[k]);
  }

  std::unique_ptr<thetad::Controller> clone() const override { return std::make_unique<ExportedController>(*this); }

 private:
  using State = exported::State<T>;
  std::string name_;
  std::unique_ptr<State> state_;
};

template <class T>
thetad::ControllerFactory factory(const std::string& name) {
  return [name](const thetad::Settings& settings, const thetad::ControllerContext& context) -> std::unique_ptr<thetad::Controller> {
    settings.allow_only({});
    if (context.settings_only) return nullptr;
    thetad::helicopter_of(context, name);  // throws for another plant: the step holds the helicopter's SDC
    return std::make_unique<ExportedController<T>>(name);
  };
}

const std::string label = exported::kLabel;
const thetad::ControllerRegistration double_step(
    label + "-exported", "the exported " + label + " (" + exported::kController + ") step in double, from " +
                             THETAD_EXPORTED_HEADER + " (docs/onboard.md); no settings",
    factory<double>(label + "-exported"));
const thetad::ControllerRegistration float_step(
    label + "-float", "the exported " + label + " (" + exported::kController + ") step in float, from " +
                          THETAD_EXPORTED_HEADER + " (docs/onboard.md); no settings",
    factory<float>(label + "-float"));

}  // namespace
