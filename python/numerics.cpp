// care, lqr and lyap: the Riccati and Lyapunov solvers of core/, numpy in and out.

#include <string>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>

#include "core/lyapunov.hpp"
#include "core/riccati.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"

namespace thetad::python {

namespace {

CareMethod care_method(const std::string& name) {
  if (name == "automatic") return CareMethod::automatic;
  if (name == "matrix_sign") return CareMethod::matrix_sign;
  if (name == "schur") return CareMethod::schur;
  throw py::value_error("care: method '" + name + "' is unknown (automatic, matrix_sign or schur)");
}

MatrixArgument square(py::handle value, const std::string& what) {
  MatrixArgument matrix(value, what);
  if (matrix.rows() != matrix.cols()) {
    std::string message = what;
    message += ": expected a square shape (n, n), got (" + std::to_string(matrix.rows()) + ", ";
    message += std::to_string(matrix.cols()) + ")";
    throw py::value_error(message);
  }
  return matrix;
}

// The four matrices of A'P + PA − PBR⁻¹B'P + Q = 0, shapes checked against A and B.
CareResult solve(const char* function, py::handle a, py::handle b, py::handle q, py::handle r, const std::string& method,
                 bool estimates) {
  const std::string name = function;
  const MatrixArgument A = square(a, name + ": A");
  const Eigen::Index n = A.rows();
  const MatrixArgument B(b, name + ": B", n);
  const Eigen::Index m = B.cols();
  const MatrixArgument Q(q, name + ": Q", n, n);
  const MatrixArgument R(r, name + ": R", m, m);
  const CareMethod chosen = care_method(method);
  py::gil_scoped_release unlocked;
  return solve_care(A.matrix(), B.matrix(), Q.matrix(), R.matrix(), chosen,
                    estimates ? ErrorEstimates::on : ErrorEstimates::off);
}

}  // namespace

void bind_numerics(py::module_& module) {
  py::class_<CareResult>(module, "CareResult",
                         "The stabilizing solution of a CARE. Unpacks as (K, P, eigenvalues), as python-control's lqr.")
      .def_readonly("P", &CareResult::P, "stabilizing solution, exactly symmetric (n, n)")
      .def_readonly("K", &CareResult::K, "optimal gain R⁻¹B'P (m, n): u = −K x")
      .def_readonly("eigenvalues", &CareResult::closed_loop_eigenvalues, "eig(A − BK), all in the open left half-plane")
      .def_readonly("residual", &CareResult::relative_residual,
                    "‖A'P + PA − PBR⁻¹B'P + Q‖_F / max(1, ‖Q‖_F)")
      .def_readonly("iterations", &CareResult::iterations, "Newton refinement steps after the direct solve")
      .def_readonly("sign_iterations", &CareResult::sign_iterations,
                    "inversions of the matrix-sign iteration (0 when P came from the Schur form)")
      .def_readonly("forward_error", &CareResult::forward_error,
                    "estimate of ‖P − P_exact‖_F / ‖P_exact‖_F (care(..., estimates=True); NaN otherwise)")
      .def_readonly("condition", &CareResult::condition,
                    "relative condition number of P, bounded as in docs/care-estimates.md (care(..., "
                    "estimates=True); NaN otherwise)")
      .def("__iter__", [](const CareResult& r) { return py::iter(py::make_tuple(r.K, r.P, r.closed_loop_eigenvalues)); })
      .def("__repr__", [](const CareResult& r) {
        return "CareResult(n=" + std::to_string(r.P.rows()) + ", m=" + std::to_string(r.K.rows()) +
               ", residual=" + py::repr(py::float_(r.relative_residual)).cast<std::string>() + ")";
      });

  module.def(
      "care",
      [](py::handle A, py::handle B, py::handle Q, py::handle R, const std::string& method, bool estimates) {
        return solve("care", A, B, Q, R, method, estimates);
      },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"), py::arg("method") = "automatic",
      py::arg("estimates") = false,
      "Solves A'P + PA − PBR⁻¹B'P + Q = 0 for the stabilizing P. method: 'automatic' (the matrix sign "
      "function, Laub's Schur method when it cannot answer), 'matrix_sign' or 'schur'. estimates=True also "
      "fills the result's forward_error and condition (docs/care-estimates.md). Raises thetad.Error "
      "naming the broken precondition (not stabilizable, Hamiltonian eigenvalues on the imaginary axis, ...).");
  module.def(
      "lqr",
      [](py::handle A, py::handle B, py::handle Q, py::handle R) { return solve("lqr", A, B, Q, R, "automatic", false); },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"),
      "The infinite-horizon LQR of ẋ = Ax + Bu with cost ∫ x'Qx + u'Ru: K, P, eigenvalues = thetad.lqr(A, B, Q, R).");
  module.def(
      "lyap",
      [](py::handle a, py::handle q) {
        const MatrixArgument A = square(a, "lyap: A");
        const MatrixArgument Q(q, "lyap: Q", A.rows(), A.rows());
        py::gil_scoped_release unlocked;
        return solve_lyapunov(A.matrix(), Q.matrix());
      },
      py::arg("A"), py::arg("Q"),
      "Solves A'X + XA + Q = 0 (note the transpose: python-control's lyap(A, Q) solves AX + XA' + Q = 0, "
      "which is thetad.lyap(A.T, Q)).");
}

}  // namespace thetad::python
