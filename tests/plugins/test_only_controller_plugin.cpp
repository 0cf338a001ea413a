// A controller that exists only for the tests of "a controller is one file": registered here and
// nowhere else, it must reach every front end (list, run, compare, bench, a campaign, Python) with
// no other edit. It holds the hover trim input and says it iterated twice per step, so that the
// benchmark's iterations column is seen to come from the controller itself; it logs a column of its
// own, its steps since reset, so that the log is seen to admit the controller's columns.
#include <memory>

#include "controllers/registry.hpp"

namespace {

class TestOnlyController : public thetad::NamedController<"test-only"> {
 public:
  explicit TestOnlyController(Eigen::VectorXd trim) : trim_(std::move(trim)) {}

  void reset(const Eigen::VectorXd&, double) override { steps_ = 0; }
  void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const thetad::Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u = trim_;
    ++steps_;
  }
  int last_iterations() const override { return 2; }
  std::vector<thetad::ControllerColumn> log_columns() const override { return {{{"steps", ""}}}; }
  void log_values(std::vector<double>& row) const override { row.push_back(steps_); }
  std::unique_ptr<thetad::Controller> clone() const override { return std::make_unique<TestOnlyController>(*this); }

 private:
  Eigen::VectorXd trim_;
  int steps_ = 0;
};

const thetad::ControllerRegistration registration = thetad::register_controller<TestOnlyController>(
    "holds the design point's input (a test plug-in: a controller known to no list)",
    [](const thetad::Settings& settings, const thetad::ControllerContext& context) -> std::unique_ptr<thetad::Controller> {
      settings.allow_only({});
      if (context.settings_only) return nullptr;
      return std::make_unique<TestOnlyController>(context.defaults.input);
    });

}  // namespace
