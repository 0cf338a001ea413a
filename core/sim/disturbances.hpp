#pragma once

#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/log_column.hpp"
#include "core/sdc_plant.hpp"
#include "core/sim/run_summary.hpp"

namespace thetad::sim {

// What stands between a controller and its plant in one run: the plant as it truly is (drawn
// parameters), what it meets (wind), what the controller sees of it (sensor noise), what reaches
// it (actuator noise and limits), and when it has gone too far. simulate() flies every plant
// through this interface; the helicopter implements it with the paper's disturbances
// (HelicopterDisturbances), any other plant gets NoDisturbances.
//
// simulate() calls, in this order: start() once; check() on the initial state; then per controller
// sample sample(), measure(), the controller, actuate(), log_values(), and after every RK4 step
// check() then advance(); finish() at the end. Every call but start() and finish() is on the hot path: no allocation.
class Disturbances {
 public:
  virtual ~Disturbances() = default;

  // Draws what is fixed for the run from `rng` (the run's only generator) and returns the plant the
  // run flies, which must live as long as this object.
  virtual const SdcPlant& start(std::mt19937_64& rng) = 0;
  // The draws and the environment of the controller sample at t (state x).
  virtual void sample(double t, const Eigen::VectorXd& x, std::mt19937_64& rng) = 0;
  // The state the controller sees (all n entries).
  virtual void measure(const Eigen::VectorXd& x, const Reference& reference, Eigen::Ref<Eigen::VectorXd> measured) = 0;
  // The input the plant receives for `command`; the reason the run ends here, with the time, or nothing.
  virtual std::optional<std::string> actuate(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& command,
                                             Eigen::VectorXd& applied) = 0;
  // Why the state x at time t counts as diverged, or nothing.
  virtual std::optional<std::string> check(const Eigen::VectorXd& x, double t) const = 0;
  // What moves at the plant rate (turbulence) after an RK4 step of dt that ended at t in state x.
  // Nothing (the default) for disturbances that change only per controller sample.
  virtual void advance(double t, double dt, const Eigen::VectorXd& x) {
    (void)t;
    (void)dt;
    (void)x;
  }
  // The log columns this object adds after the applied input, and their values for the last sample.
  // Whether the last actuate() held an input channel at a magnitude bound: what the anti-windup of
  // the position integrals acts on (the rate limit, which filters the actuator noise at most
  // samples, does not count). Never (the default) for disturbances without limits.
  virtual bool input_limited() const { return false; }
  virtual std::vector<LogColumn> log_columns() const { return {}; }
  virtual void log_values(std::vector<double>& row) const { (void)row; }
  // What the summary says of the run's conditions: drawn parameters, model options, saturation.
  virtual void finish(RunSummary& summary) const { (void)summary; }
};

// Any plant as it is: no draws, the true state measured, the command applied as it is; diverged
// when the state is not finite or leaves |x|_inf <= max_state.
class NoDisturbances final : public Disturbances {
 public:
  explicit NoDisturbances(const SdcPlant& plant, double max_state = 1e6) : plant_(plant), max_state_(max_state) {}

  const SdcPlant& start(std::mt19937_64&) override { return plant_; }
  void sample(double, const Eigen::VectorXd&, std::mt19937_64&) override {}
  void measure(const Eigen::VectorXd& x, const Reference&, Eigen::Ref<Eigen::VectorXd> measured) override {
    measured = x;
  }
  std::optional<std::string> actuate(double, const Eigen::VectorXd&, const Eigen::VectorXd& command,
                                     Eigen::VectorXd& applied) override {
    applied = command;
    return std::nullopt;
  }
  std::optional<std::string> check(const Eigen::VectorXd& x, double t) const override;

 private:
  const SdcPlant& plant_;
  double max_state_;
};

}  // namespace thetad::sim
