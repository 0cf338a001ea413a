#pragma once

// A plant written in Python (`class MyPlant(thetad.Plant)`, python/thetad/plant.py) as the SdcPlant
// that the simulator and the controllers fly. What the class says about itself (dimensions, names,
// design defaults, initial state, whether F and B depend on u, whether it has a Jacobian) is read
// and checked once, when the PythonPlant is made, so that a flight calls into Python only for f,
// sdc and jacobian. Those take the GIL (the simulator flies with it released, possibly on another
// thread), call the object's method and check the shape and finiteness of what it returns: a
// Python exception or a wrong result becomes a PlantCodeError naming the class and the method, so
// the run ends as failed with that reason and Python is never torn down. The object stays alive as long as
// C++ holds the plant. Slower than a plant in C++, and exempt from the zero-allocation rule
// (docs/python.md, "A plant written in Python").

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <pybind11/pybind11.h>

#include "core/sdc_plant.hpp"

namespace thetad::python {

namespace py = pybind11;

class PythonPlant final : public SdcPlant {
 public:
  // `object` must be a thetad.Plant instance; with the GIL held. TypeError or ValueError, naming the
  // class and the attribute, for what it lacks or gives wrong.
  explicit PythonPlant(py::object object);
  ~PythonPlant() override;
  PythonPlant(const PythonPlant&) = delete;
  PythonPlant& operator=(const PythonPlant&) = delete;

  // "python:Pendulum" for class Pendulum: the plant's name in results, as a Python controller's is.
  const std::string& name() const { return name_; }
  // The class's initial_state, where a flight starts when the caller gives none.
  const std::optional<Eigen::VectorXd>& initial_state() const { return initial_state_; }

  int state_dim() const override { return state_dim_; }
  int input_dim() const override { return input_dim_; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  // False, writing nothing, when the class defines no jacobian (or sets it to None).
  bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const override;
  bool sdc_depends_on_input() const override { return sdc_depends_on_input_; }
  std::vector<LogColumn> state_columns() const override { return state_columns_; }
  std::vector<LogColumn> input_columns() const override { return input_columns_; }
  DesignDefaults design_defaults() const override { return design_defaults_; }

 private:
  // Calls the object's `method` with copies of x and u, the GIL taken, and hands its result to
  // `take`; what either raises becomes a PlantCodeError naming CLASS.METHOD.
  template <class Take>
  void call(const char* method, const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
            Take&& take) const;
  std::vector<LogColumn> columns(const char* attribute, std::vector<LogColumn> defaults) const;
  DesignDefaults read_design_defaults() const;

  py::object object_;
  std::string class_name_;
  std::string name_;
  int state_dim_ = 0;
  int input_dim_ = 0;
  bool sdc_depends_on_input_ = false;
  bool has_jacobian_ = false;
  std::vector<LogColumn> state_columns_;
  std::vector<LogColumn> input_columns_;
  DesignDefaults design_defaults_;
  std::optional<Eigen::VectorXd> initial_state_;
};

}  // namespace thetad::python
