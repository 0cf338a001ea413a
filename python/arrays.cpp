#include "python/arrays.hpp"

namespace thetad::python {

namespace {

std::string dimension(Eigen::Index size, const char* symbol) {
  return size == kAny ? std::string(symbol) : std::to_string(size);
}

std::string shape_of(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    if (i > 0) text += ", ";
    text += std::to_string(array.shape(i));
  }
  if (array.ndim() == 1) text += ",";
  return text + ")";
}

// The value as a float64 array of the layout `Array` asks for; TypeError when it is none.
template <class Array>
Array real_array(py::handle value, const std::string& what, const char* kind) {
  // Complex, string and object arrays would convert only by losing or inventing values.
  const py::array given = py::array::ensure(value);
  if (!given || given.dtype().kind() == 'c' || given.dtype().kind() == 'O' || given.dtype().kind() == 'U' ||
      given.dtype().kind() == 'S' || given.dtype().kind() == 'V') {
    std::string message = what;
    message += ": expected a real ";
    message += kind;
    message += " (a float array or nested lists of numbers), got ";
    message += py::str(py::type::of(value).attr("__name__")).cast<std::string>();
    throw py::type_error(message);
  }
  return Array::ensure(given);
}

}  // namespace

MatrixArgument::MatrixArgument(py::handle value, const std::string& what, Eigen::Index rows, Eigen::Index cols) {
  using Array = py::array_t<double, py::array::f_style | py::array::forcecast>;
  const std::string expected = "(" + dimension(rows, "n") + ", " + dimension(cols, "m") + ")";
  Array array = real_array<Array>(value, what, "matrix");
  if (array.ndim() != 2 || (rows != kAny && array.shape(0) != rows) || (cols != kAny && array.shape(1) != cols)) {
    std::string message = what;
    message += ": expected shape ";
    message += expected;
    message += ", got ";
    message += shape_of(array);
    throw py::value_error(message);
  }
  array_ = std::move(array);
}

Eigen::Map<const Eigen::MatrixXd> MatrixArgument::matrix() const { return {array_.data(), rows(), cols()}; }

VectorArgument::VectorArgument(py::handle value, const std::string& what, Eigen::Index size) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  Array array = real_array<Array>(value, what, "vector");
  if (array.ndim() != 1 || (size != kAny && array.shape(0) != size)) {
    std::string message = what;
    message += ": expected shape (";
    message += dimension(size, "n");
    message += ",), got ";
    message += shape_of(array);
    throw py::value_error(message);
  }
  array_ = std::move(array);
}

Eigen::Map<const Eigen::VectorXd> VectorArgument::vector() const { return {array_.data(), size()}; }

}  // namespace thetad::python
