// A plug-in controller that breaks on purpose, for the tests of what a faulty user controller does
// to a run: holds hover thrust until `at` seconds, then throws a std::runtime_error (not a
// thetad::Error, as a user's code would), returns NaN, or returns Inf (`fault`).
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "controllers/registry.hpp"

namespace {

class FaultyController : public thetad::Controller {
 public:
  FaultyController(std::string fault, double at, double hover_thrust)
      : fault_(std::move(fault)), at_(at), hover_thrust_(hover_thrust) {}

  std::string name() const override { return "faulty"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>&, const thetad::Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u.setZero();
    u[0] = hover_thrust_;
    if (t < at_) return;
    if (fault_ == "throw") throw std::runtime_error("the user's code threw");
    u[2] = fault_ == "nan" ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
  }
  std::unique_ptr<thetad::Controller> clone() const override { return std::make_unique<FaultyController>(*this); }

 private:
  std::string fault_;
  double at_;
  double hover_thrust_;
};

const thetad::ControllerRegistration registration(
    "faulty", "fails on purpose at `at` s: `fault` throw|nan|inf (a test plug-in)",
    [](const thetad::Settings& settings, const thetad::ControllerContext& context) -> std::unique_ptr<thetad::Controller> {
      settings.allow_only({"fault", "at"});
      const std::string fault = settings.choice("fault", "throw", {"throw", "nan", "inf"});
      const double at = settings.number("at", 0.05, 0.0);
      if (context.settings_only) return nullptr;
      return std::make_unique<FaultyController>(fault, at, context.defaults.input[0]);
    });

}  // namespace
