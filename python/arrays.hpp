#pragma once

// numpy arguments checked at the boundary: a value that is no real array raises TypeError, one of
// the wrong shape ValueError, both naming the argument and the shape expected, before any C++ sees
// it. A float64 array in column-major (Fortran) order is used in place; others are converted once.

#include <string>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace thetad::python {

namespace py = pybind11;

// "any size" for one dimension of an expected shape.
inline constexpr Eigen::Index kAny = -1;

class MatrixArgument {
 public:
  // `what` names the argument in messages ("care: A"); `rows`/`cols` are kAny or the size required.
  MatrixArgument(py::handle value, const std::string& what, Eigen::Index rows = kAny, Eigen::Index cols = kAny);
  Eigen::Map<const Eigen::MatrixXd> matrix() const;
  Eigen::Index rows() const { return array_.shape(0); }
  Eigen::Index cols() const { return array_.shape(1); }

 private:
  py::array_t<double, py::array::f_style | py::array::forcecast> array_;
};

class VectorArgument {
 public:
  VectorArgument(py::handle value, const std::string& what, Eigen::Index size = kAny);
  Eigen::Map<const Eigen::VectorXd> vector() const;
  Eigen::Index size() const { return array_.shape(0); }

 private:
  py::array_t<double, py::array::c_style | py::array::forcecast> array_;
};

}  // namespace thetad::python
