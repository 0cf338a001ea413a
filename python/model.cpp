// The helicopter: f(x, u), its state-dependent coefficients, its exact linearization, trims, and the
// Table 1 draw of a seed.

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "controllers/linearization.hpp"
#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "core/sim/simulator.hpp"
#include "core/trim.hpp"
#include "experiment/demo_diagnostics.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "python/values.hpp"

namespace thetad::python {

namespace {

using heli::kInputDim;
using heli::kStateDim;

// The helicopter's state and input names (x_p, ..., s; T_mr, ..., delta_lat), as its log spells them.
std::vector<std::string> names_of(const std::vector<LogColumn>& columns) {
  std::vector<std::string> names;
  for (const auto& column : columns) names.push_back(column.name);
  return names;
}

const std::vector<std::string>& state_names() {
  static const std::vector<std::string> names = names_of(heli::Helicopter().state_columns());
  return names;
}

const std::vector<std::string>& input_names() {
  static const std::vector<std::string> names = names_of(heli::Helicopter().input_columns());
  return names;
}

// A switch's value in the spelling ModelOptions::set reads: True/False -> on/off, ±1, names.
std::string switch_value(const std::string& name, py::handle value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "on" : "off";
  if (py::isinstance<py::int_>(value)) return std::to_string(value.cast<long long>());
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw py::type_error("Helicopter: switch '" + name + "' takes a bool, +1/-1 or a name, got " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

heli::ModelOptions model_options(const std::string& preset, const py::kwargs& switches) {
  heli::ModelOptions options = heli::ModelOptions::preset(preset);
  for (const auto& [key, value] : switches) {
    const std::string name = key.cast<std::string>();
    options.set(name, switch_value(name, value));
  }
  return options;
}

// The Table 1 parameter draw a run with `seed` makes first (core/sim/simulator.hpp).
heli::PerturbedParameters draw(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return heli::perturbed_parameters(heli::Parameters::nominal(), rng);
}

py::list report_rows(const std::vector<heli::UncertaintyReport>& report) {
  py::list rows;
  for (const auto& entry : report) {
    py::dict row;
    row["number"] = entry.number;
    row["name"] = entry.name;
    row["percent"] = entry.percent;
    row["category"] = std::string(heli::to_string(entry.category));
    row["per_sample"] = entry.per_sample;
    row["xi"] = entry.xi;
    row["factor"] = entry.factor;
    rows.append(row);
  }
  return rows;
}

py::dict options_of(const heli::Helicopter& plant) {
  py::dict options;
  for (const auto name : heli::ModelOptions::names) options[py::str(std::string(name))] = plant.options().get(name);
  return options;
}

std::string repr(const Eigen::VectorXd& v) { return py::repr(py::cast(v)).cast<std::string>(); }

// ∂f/∂x and ∂f/∂u at (x, u) from the plant's own Jacobian (SdcPlant::jacobian: by hand for the
// helicopter), not by differences.
Linearization exact_linearization(const SdcPlant& plant, py::handle x, py::handle u) {
  const VectorArgument state(x, "linearize: x", plant.state_dim());
  const VectorArgument input(u, "linearize: u", plant.input_dim());
  Linearization linear{Eigen::MatrixXd(plant.state_dim(), plant.state_dim()),
                       Eigen::MatrixXd(plant.state_dim(), plant.input_dim())};
  py::gil_scoped_release unlocked;
  if (!plant.jacobian(state.vector(), input.vector(), linear.A, linear.B))
    throw Error("linearize: the plant has no exact Jacobian");
  return linear;
}

}  // namespace

void bind_model(py::module_& module) {
  module.attr("state_names") = state_names();
  module.attr("input_names") = input_names();

  py::class_<Trim>(module, "Trim", "An equilibrium of the helicopter (core/trim.hpp)")
      .def_readonly("state", &Trim::state, "18-state: the commanded position and heading, s = 1")
      .def_readonly("input", &Trim::input, "[T_mr, delta_ped, delta_col, delta_lon, delta_lat]")
      .def_readonly("rotor_speed", &Trim::rotor_speed, "Omega_mr (rad/s)")
      .def_readonly("residual", &Trim::residual, "distance from the commanded motion")
      .def_readonly("solver_status", &Trim::solver_status)
      .def_readonly("iterations", &Trim::iterations)
      .def("__repr__", [](const Trim& t) {
        return "Trim(input=" + repr(t.input) + ", rotor_speed=" + py::repr(py::float_(t.rotor_speed)).cast<std::string>() +
               ", residual=" + py::repr(py::float_(t.residual)).cast<std::string>() + ")";
      });

  py::class_<DesignDefaults>(module, "DesignDefaults",
                             "A plant's design defaults: the diagonals of Q and R and the input u0 where the first "
                             "SDC is taken. Unpacks as (q, r, u0).")
      .def_readonly("state_weights", &DesignDefaults::state_weights, "diagonal of Q (n,)")
      .def_readonly("input_weights", &DesignDefaults::input_weights, "diagonal of R (m,)")
      .def_readonly("input", &DesignDefaults::input, "u0 (m,): the hover thrust m g for the helicopter")
      .def("__iter__",
           [](const DesignDefaults& d) { return py::iter(py::make_tuple(d.state_weights, d.input_weights, d.input)); })
      .def("__repr__", [](const DesignDefaults& d) {
        return "DesignDefaults(state_weights=" + repr(d.state_weights) + ", input_weights=" + repr(d.input_weights) +
               ", input=" + repr(d.input) + ")";
      });

  py::class_<Linearization>(module, "Linearization", "ẋ ≈ f(x*, u*) + A (x − x*) + B (u − u*). Unpacks as (A, B).")
      .def_readonly("A", &Linearization::A, "∂f/∂x (n, n)")
      .def_readonly("B", &Linearization::B, "∂f/∂u (n, m)")
      .def("__iter__", [](const Linearization& l) { return py::iter(py::make_tuple(l.A, l.B)); })
      .def("__repr__", [](const Linearization& l) {
        return "Linearization(n=" + std::to_string(l.A.rows()) + ", m=" + std::to_string(l.B.cols()) + ")";
      });

  module.def(
      "linearize", [](const heli::Helicopter& plant, py::handle x, py::handle u) { return exact_linearization(plant, x, u); },
      py::arg("plant"), py::arg("x"), py::arg("u"),
      "The plant's exact Jacobians at (x, u), from its hand-written derivatives: A, B = thetad.linearize(plant, x, u).");

  module.def(
      "demo", [] { return to_python(demo_json(demo_diagnostics())); },
      "What `thetad demo` checks before anything flies, as demo.json holds it: the CARE at the initial state with "
      "the paper's weights (residual, closed-loop poles, diag T0), Newton-Kleinman from 1.01 P, the hover trim at "
      "3.5 m, and the build.");

  module.def(
      "uncertainty_draw", [](std::uint64_t seed) { return report_rows(draw(seed).report); }, py::arg("seed"),
      "The 45 rows of Table 1 as a run with this seed draws them (a dict per row: number, name, percent, "
      "category, per_sample, xi, factor); the parameter rows are what Helicopter(seed=...) flies.");

  py::class_<heli::Helicopter>(module, "Helicopter",
                               "The X-Cell 60 over the 18-state augmented vector (docs/model.md): ẋ = f(x, u) = F(x)x + B(x)u.")
      .def(py::init([](const std::string& preset, std::optional<std::uint64_t> seed, const py::kwargs& switches) {
             const heli::ModelOptions options = model_options(preset, switches);
             return heli::Helicopter(seed ? draw(*seed).parameters : heli::Parameters::nominal(), options);
           }),
           py::arg("preset") = "resolved", py::kw_only(), py::arg("seed") = py::none(),
           "preset: 'resolved' (default) or 'paper'; seed: the Table 1 parameters a run with that seed flies "
           "(none: nominal); any model switch of docs/model.md §11 by name, e.g. rotor_speed_model='governor'.")
      .def_property_readonly_static("state_names", [](py::handle) { return state_names(); })
      .def_property_readonly_static("input_names", [](py::handle) { return input_names(); })
      .def_property_readonly("state_dim", &heli::Helicopter::state_dim)
      .def_property_readonly("input_dim", &heli::Helicopter::input_dim)
      .def_property_readonly("options", &options_of)
      .def("__repr__",
           [](const heli::Helicopter& plant) { return "Helicopter(" + py::repr(options_of(plant)).cast<std::string>() + ")"; })
      .def(
          "f",
          [](const heli::Helicopter& plant, py::handle x, py::handle u) {
            const VectorArgument state(x, "Helicopter.f: x", kStateDim);
            const VectorArgument input(u, "Helicopter.f: u", kInputDim);
            return plant.f(state.vector(), input.vector());
          },
          py::arg("x"), py::arg("u"), "ẋ (18,) at state x (18,) and input u (5,)")
      .def(
          "sdc",
          [](const heli::Helicopter& plant, py::handle x, py::handle u) {
            const VectorArgument state(x, "Helicopter.sdc: x", kStateDim);
            const Eigen::VectorXd input =
                u.is_none() ? plant.design_defaults().input : Eigen::VectorXd(VectorArgument(u, "Helicopter.sdc: u", kInputDim).vector());
            auto coefficients = plant.sdc(state.vector(), input);
            return py::make_tuple(std::move(coefficients.F), std::move(coefficients.B));
          },
          py::arg("x"), py::arg("u") = py::none(),
          "(F, B) with F x + B u == f(x, u); u sets the rotor speed (default: hover thrust m g)")
      .def("design_defaults", &heli::Helicopter::design_defaults,
           "DesignDefaults (diag Q, diag R, u0; unpacks as that tuple): the paper's weights and hover thrust")
      .def(
          "trim",
          [](const heli::Helicopter& plant, double altitude, double speed, double course, double climb_rate,
             double heading) {
            py::gil_scoped_release unlocked;
            return find_trim(plant, TrimCondition::straight(speed, course, climb_rate, altitude, heading));
          },
          py::arg("altitude"), py::arg("speed") = 0.0, py::arg("course") = 0.0, py::arg("climb_rate") = 0.0,
          py::arg("heading") = 0.0,
          "The equilibrium (Ipopt) for straight flight at `speed` m/s along `course` rad, climbing at "
          "`climb_rate` m/s, at `altitude` m and `heading` rad; hover by default.");
}

}  // namespace thetad::python
