#pragma once

// Controllers crossing the language boundary.
//  - PythonController: the trampoline behind `class MyController(thetad.Controller)`. The simulator
//    calls control() with the GIL released; control() takes the GIL, calls the Python compute(t, x,
//    reference) and checks what it returns. A Python exception (or a wrong result) becomes a
//    thetad::Error naming the class, so the run ends as failed with that reason, never a crash.
//  - BorrowedController: how a Python-owned controller flies in C++. It holds a reference to the
//    Python object (keeping it alive as long as C++ holds the controller) and forwards to it.
//  - RegisteredController: a registered controller built from its name and settings for a flight's
//    model (thetad.controller()); it keeps that Flight alive and remembers its spec, so that run()
//    builds the same controller again for the flight it flies.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/pybind11.h>

#include "controllers/controller.hpp"
#include "experiment/flight.hpp"

namespace thetad::python {

namespace py = pybind11;

class PythonController : public Controller {
 public:
  std::string name() const override;
  void reset(const Eigen::VectorXd& x0, double t0) override;
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;
  // The Python clone() when the class defines one (it must return an independent thetad.Controller);
  // otherwise a second handle on this very object, which therefore shares its state.
  std::unique_ptr<Controller> clone() const override;

  // "PD" for class PD: what messages and the default label call it.
  std::string class_name() const;
};

class BorrowedController final : public Controller {
 public:
  // `object` must be a thetad.Controller instance; it stays alive while this lives.
  explicit BorrowedController(py::object object);
  ~BorrowedController() override;
  BorrowedController(const BorrowedController&) = delete;
  BorrowedController& operator=(const BorrowedController&) = delete;

  std::string name() const override { return target_->name(); }
  void reset(const Eigen::VectorXd& x0, double t0) override { target_->reset(x0, t0); }
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override {
    target_->control(t, measured_state, reference, u);
  }
  std::vector<std::pair<std::string, double>> counters() const override { return target_->counters(); }
  std::vector<ControllerColumn> log_columns() const override { return target_->log_columns(); }
  void log_values(std::vector<double>& row) const override { target_->log_values(row); }
  int last_iterations() const override { return target_->last_iterations(); }
  std::unique_ptr<Controller> clone() const override { return target_->clone(); }

 private:
  py::object object_;
  Controller* target_;
};

class RegisteredController final : public Controller {
 public:
  RegisteredController(std::shared_ptr<const Flight> flight, PreparedController prepared);

  const ControllerSpec& spec() const { return prepared_.spec; }
  const YAML::Node& settings() const { return prepared_.settings; }
  const Flight& flight() const { return *flight_; }

  std::string name() const override { return prepared_.controller->name(); }
  void reset(const Eigen::VectorXd& x0, double t0) override { prepared_.controller->reset(x0, t0); }
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override {
    prepared_.controller->control(t, measured_state, reference, u);
  }
  std::vector<std::pair<std::string, double>> counters() const override { return prepared_.controller->counters(); }
  std::vector<ControllerColumn> log_columns() const override {
    return prepared_.controller->log_columns();
  }
  void log_values(std::vector<double>& row) const override { prepared_.controller->log_values(row); }
  int last_iterations() const override { return prepared_.controller->last_iterations(); }
  std::unique_ptr<Controller> clone() const override;

 private:
  std::shared_ptr<const Flight> flight_;  // the model the controller refers to
  PreparedController prepared_;
};

}  // namespace thetad::python
