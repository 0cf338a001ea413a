#include "python/python_plant.hpp"

#include <utility>

#include <pybind11/numpy.h>

#include "core/error.hpp"
#include "core/plant_code_error.hpp"
#include "python/arrays.hpp"
#include "python/python_errors.hpp"

namespace thetad::python {

namespace {

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")).cast<std::string>(); }

// An int, or anything that is one (numpy's integers).
int dimension(const py::object& object, const std::string& what) {
  const bool whole = PyIndex_Check(object.ptr()) && !py::isinstance<py::bool_>(object);
  const long long value = whole ? py::int_(object).cast<long long>() : 0;
  if (value < 1 || value > 100000)
    throw py::value_error(what + " must be a positive int, got " + py::repr(object).cast<std::string>());
  return static_cast<int>(value);
}

// The two arrays a method returns as a pair, (F, B) or (A, B).
std::pair<py::object, py::object> pair_of(const py::object& result, const std::string& method, const char* pair) {
  if (!(py::isinstance<py::tuple>(result) || py::isinstance<py::list>(result)) || py::len(result) != 2)
    throw PlantCodeError(method + " must return " + pair + ", got " + type_name(result));
  const py::sequence items = result;
  return {items[0], items[1]};
}

// A result's vector, checked to be finite: a NaN from a plant's Python code would otherwise show
// only as the run's divergence, far from where it came from.
void take_vector(const py::object& value, const std::string& what, Eigen::Index size, Eigen::Ref<Eigen::VectorXd> into) {
  const VectorArgument checked(value, what, size);
  if (!checked.vector().allFinite()) throw PlantCodeError(what + " with a NaN or an infinity");
  into = checked.vector();
}

void take_matrix(const py::object& value, const std::string& what, Eigen::Index rows, Eigen::Index cols,
                 Eigen::Ref<Eigen::MatrixXd> into) {
  const MatrixArgument checked(value, what, rows, cols);
  if (!checked.matrix().allFinite()) throw PlantCodeError(what + " with a NaN or an infinity");
  into = checked.matrix();
}

Eigen::VectorXd read_vector(const py::object& value, const std::string& what, Eigen::Index size) {
  const VectorArgument checked(value, what, size);
  if (!checked.vector().allFinite()) throw py::value_error(what + " has a NaN or an infinity");
  return checked.vector();
}

}  // namespace

PythonPlant::PythonPlant(py::object object)
    : object_(std::move(object)),
      class_name_(py::str(py::type::of(object_).attr("__qualname__")).cast<std::string>()),
      name_("python:" + class_name_) {
  for (const char* method : {"f", "sdc"}) {
    if (!py::hasattr(object_, method) || !py::isinstance<py::function>(object_.attr(method)))
      throw py::type_error(class_name_ + " does not define " + method + "(self, x, u)");
  }
  state_dim_ = dimension(object_.attr("state_dim"), class_name_ + ".state_dim");
  input_dim_ = dimension(object_.attr("input_dim"), class_name_ + ".input_dim");
  sdc_depends_on_input_ = py::bool_(object_.attr("sdc_depends_on_input")).cast<bool>();
  has_jacobian_ = !object_.attr("jacobian").is_none();
  state_columns_ = columns("state_names", SdcPlant::state_columns());
  input_columns_ = columns("input_names", SdcPlant::input_columns());
  design_defaults_ = read_design_defaults();
  if (const py::object x0 = object_.attr("initial_state"); !x0.is_none())
    initial_state_ = read_vector(x0, class_name_ + ".initial_state", state_dim_);
}

PythonPlant::~PythonPlant() {
  // The last C++ reference may go on a thread that does not hold the GIL.
  py::gil_scoped_acquire gil;
  object_ = py::object();
}

// Each name is "theta" or ("theta", "rad"): the log's column theta_rad.
std::vector<LogColumn> PythonPlant::columns(const char* attribute, std::vector<LogColumn> defaults) const {
  const py::object names = object_.attr(attribute);
  if (names.is_none()) return defaults;
  const std::string what = class_name_ + "." + attribute;
  if (py::isinstance<py::str>(names) || !py::isinstance<py::sequence>(names) || py::len(names) != defaults.size())
    throw py::value_error(what + " must be a list of " + std::to_string(defaults.size()) +
                          " names (\"name\" or (\"name\", \"unit\")), got " + py::repr(names).cast<std::string>());
  std::vector<LogColumn> columns;
  for (const py::handle name : names) {
    if (py::isinstance<py::str>(name)) {
      columns.push_back({name.cast<std::string>(), ""});
    } else if (py::isinstance<py::tuple>(name) && py::len(name) == 2 && py::isinstance<py::str>(name[py::int_(0)]) &&
               py::isinstance<py::str>(name[py::int_(1)])) {
      columns.push_back({name[py::int_(0)].cast<std::string>(), name[py::int_(1)].cast<std::string>()});
    } else {
      throw py::value_error(what + ": each name is \"name\" or (\"name\", \"unit\"), got " +
                            py::repr(name).cast<std::string>());
    }
    if (columns.back().name.empty()) throw py::value_error(what + ": a name is empty");
    for (std::size_t i = 0; i + 1 < columns.size(); ++i) {
      if (columns[i].header() == columns.back().header())
        throw py::value_error(what + ": two columns would be called " + columns[i].header());
    }
  }
  return columns;
}

// design_defaults(self) -> (diag Q, diag R, u0), each None for the SdcPlant default.
DesignDefaults PythonPlant::read_design_defaults() const {
  DesignDefaults defaults = SdcPlant::design_defaults();
  const std::string what = class_name_ + ".design_defaults()";
  py::object given;
  try {
    given = object_.attr("design_defaults")();
  } catch (const py::error_already_set& error) {
    throw Error(what + " raised " + describe(error));
  }
  if (given.is_none()) return defaults;
  if (!(py::isinstance<py::tuple>(given) || py::isinstance<py::list>(given)) || py::len(given) != 3)
    throw py::value_error(what + " must return (state_weights, input_weights, input) or None, got " +
                          py::repr(given).cast<std::string>());
  const py::sequence parts = given;
  if (!parts[0].is_none()) defaults.state_weights = read_vector(parts[0], what + " state_weights", state_dim_);
  if (!parts[1].is_none()) defaults.input_weights = read_vector(parts[1], what + " input_weights", input_dim_);
  if (!parts[2].is_none()) defaults.input = read_vector(parts[2], what + " input", input_dim_);
  if ((defaults.state_weights.array() < 0.0).any())
    throw py::value_error(what + ": the state weights (diagonal of Q) must not be negative");
  if ((defaults.input_weights.array() <= 0.0).any())
    throw py::value_error(what + ": the input weights (diagonal of R) must be positive");
  return defaults;
}

template <class Take>
void PythonPlant::call(const char* method, const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& u, Take&& take) const {
  py::gil_scoped_acquire gil;
  const std::string name = class_name_ + "." + method;
  try {  // the look-up too: a Ctrl-C can be raised there
    const py::object result = object_.attr(method)(py::array(x.size(), x.data()), py::array(u.size(), u.data()));
    take(result, name);
  } catch (const py::error_already_set& error) {
    PlantCodeError failure(name + " raised " + describe(error));
    pass_on_interrupt(error);
    throw failure;
  } catch (const py::builtin_exception& error) {  // what the array checks raise for a wrong shape
    throw PlantCodeError(error.what());
  }
}

void PythonPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                    Eigen::Ref<Eigen::VectorXd> xdot) const {
  call("f", x, u, [&](const py::object& result, const std::string& name) {
    take_vector(result, name + " returned xdot", state_dim_, xdot);
  });
}

void PythonPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                      Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  call("sdc", x, u, [&](const py::object& result, const std::string& name) {
    const auto [state_part, input_part] = pair_of(result, name, "(F, B)");
    take_matrix(state_part, name + " returned F", state_dim_, state_dim_, F);
    take_matrix(input_part, name + " returned B", state_dim_, input_dim_, B);
  });
}

bool PythonPlant::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                           Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const {
  if (!has_jacobian_) return false;
  call("jacobian", x, u, [&](const py::object& result, const std::string& name) {
    const auto [by_state, by_input] = pair_of(result, name, "(A, B), the Jacobians df/dx and df/du");
    take_matrix(by_state, name + " returned A", state_dim_, state_dim_, dfdx);
    take_matrix(by_input, name + " returned B", state_dim_, input_dim_, dfdu);
  });
  return true;
}

}  // namespace thetad::python
