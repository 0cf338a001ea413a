// care, lqr, dare, dlqr and lyap: the Riccati and Lyapunov solvers of core/, numpy in and out.

#include <optional>
#include <string>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>

#include "core/dare.hpp"
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

// The matrices of a Riccati equation, shapes checked against A and B: Q, R and the optional cross
// term (S of the DARE, N of the LQR cost).
struct Equation {
  MatrixArgument A, B, Q, R;
  std::optional<MatrixArgument> cross;
};

Equation equation(const std::string& function, py::handle a, py::handle b, py::handle q, py::handle r,
                  py::handle cross = py::none(), const char* cross_name = "N") {
  MatrixArgument A = square(a, function + ": A");
  const Eigen::Index n = A.rows();
  MatrixArgument B(b, function + ": B", n);
  const Eigen::Index m = B.cols();
  Equation e{std::move(A), std::move(B), MatrixArgument(q, function + ": Q", n, n),
             MatrixArgument(r, function + ": R", m, m), {}};
  if (!cross.is_none()) e.cross.emplace(cross, function + ": " + cross_name, n, m);
  return e;
}

CareResult solve(const Equation& e, CareMethod method, bool estimates) {
  const ErrorEstimates wanted = estimates ? ErrorEstimates::on : ErrorEstimates::off;
  py::gil_scoped_release unlocked;
  if (e.cross) return solve_care(e.A.matrix(), e.B.matrix(), e.Q.matrix(), e.R.matrix(), e.cross->matrix(), method, wanted);
  return solve_care(e.A.matrix(), e.B.matrix(), e.Q.matrix(), e.R.matrix(), method, wanted);
}

DareResult solve_discrete(const Equation& e) {
  py::gil_scoped_release unlocked;
  if (e.cross) return solve_dare(e.A.matrix(), e.B.matrix(), e.Q.matrix(), e.R.matrix(), e.cross->matrix());
  return solve_dare(e.A.matrix(), e.B.matrix(), e.Q.matrix(), e.R.matrix());
}

// The part of a Riccati result that CareResult and DareResult share: the stabilizing solution (named
// `solution`), K, the closed loop's eigenvalues and the residual; unpacks as (K, solution,
// eigenvalues), the order of python-control's lqr and dlqr.
template <typename Result>
py::class_<Result> riccati_result(py::module_& module, const char* name, const char* doc, const char* solution,
                                  Eigen::MatrixXd Result::*X, const char* gain, const char* spectrum,
                                  const char* residual) {
  return py::class_<Result>(module, name, doc)
      .def_readonly(solution, X, "stabilizing solution, exactly symmetric (n, n)")
      .def_readonly("K", &Result::K, gain)
      .def_readonly("eigenvalues", &Result::closed_loop_eigenvalues, spectrum)
      .def_readonly("residual", &Result::relative_residual, residual)
      .def("__iter__", [X](const Result& r) { return py::iter(py::make_tuple(r.K, r.*X, r.closed_loop_eigenvalues)); })
      .def("__repr__", [name, X](const Result& r) {
        return std::string(name) + "(n=" + std::to_string((r.*X).rows()) + ", m=" + std::to_string(r.K.rows()) +
               ", residual=" + py::repr(py::float_(r.relative_residual)).cast<std::string>() + ")";
      });
}

}  // namespace

void bind_numerics(py::module_& module) {
  riccati_result(module, "CareResult",
                 "The stabilizing solution of a CARE. Unpacks as (K, P, eigenvalues), as python-control's lqr.", "P",
                 &CareResult::P, "optimal gain R⁻¹B'P (m, n): u = −K x",
                 "eig(A − BK), all in the open left half-plane", "‖A'P + PA − PBR⁻¹B'P + Q‖_F / max(1, ‖Q‖_F)")
      .def_readonly("iterations", &CareResult::iterations, "Newton refinement steps after the direct solve")
      .def_readonly("sign_iterations", &CareResult::sign_iterations,
                    "inversions of the matrix-sign iteration (0 when P came from the Schur form)")
      .def_readonly("forward_error", &CareResult::forward_error,
                    "estimate of ‖P − P_exact‖_F / ‖P_exact‖_F (care(..., estimates=True); NaN otherwise)")
      .def_readonly("condition", &CareResult::condition,
                    "relative condition number of P, bounded as in docs/care-estimates.md (care(..., "
                    "estimates=True); NaN otherwise)");

  riccati_result(module, "DareResult",
                 "The stabilizing solution of a DARE. Unpacks as (K, X, eigenvalues), as python-control's dlqr.", "X",
                 &DareResult::X, "optimal gain (R + B'XB)⁻¹(B'XA + S') (m, n): u = −K x",
                 "eig(A − BK), all inside the unit circle", "‖A'XA − X − (A'XB + S)K + Q‖_F / max(1, ‖Q‖_F)")
      .def_readonly("doublings", &DareResult::doublings, "steps of the structure-preserving doubling algorithm")
      .def_readonly("refinements", &DareResult::refinements, "Newton steps after the doubling (0 or 1)");

  module.def(
      "care",
      [](py::handle A, py::handle B, py::handle Q, py::handle R, const std::string& method, bool estimates) {
        return solve(equation("care", A, B, Q, R), care_method(method), estimates);
      },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"), py::arg("method") = "automatic",
      py::arg("estimates") = false,
      "Solves A'P + PA − PBR⁻¹B'P + Q = 0 for the stabilizing P. method: 'automatic' (the matrix sign "
      "function, Laub's Schur method when it cannot answer), 'matrix_sign' or 'schur'. estimates=True also "
      "fills the result's forward_error and condition (docs/care-estimates.md). Raises thetad.Error "
      "naming the broken precondition (not stabilizable, Hamiltonian eigenvalues on the imaginary axis, ...).");
  module.def(
      "lqr",
      [](py::handle A, py::handle B, py::handle Q, py::handle R, py::handle N) {
        return solve(equation("lqr", A, B, Q, R, N), CareMethod::automatic, false);
      },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"), py::arg("N") = py::none(),
      "The infinite-horizon LQR of ẋ = Ax + Bu with cost ∫ x'Qx + u'Ru + 2x'Nu: K, P, eigenvalues = "
      "thetad.lqr(A, B, Q, R[, N]) (python-control's order); N is eliminated first (A − BR⁻¹N', Q − NR⁻¹N').");
  module.def(
      "dare",
      [](py::handle A, py::handle B, py::handle Q, py::handle R, py::handle S) {
        return solve_discrete(equation("dare", A, B, Q, R, S, "S"));
      },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"), py::arg("S") = py::none(),
      "Solves X = A'XA − (A'XB + S)(R + B'XB)⁻¹(B'XA + S') + Q for the stabilizing X by structure-preserving "
      "doubling (R invertible). The result's X is scipy.linalg.solve_discrete_are(A, B, Q, R, s=S). Raises "
      "thetad.Error naming the reason (not stabilizable, a mode on the unit circle unseen by Q, R + B'XB not "
      "positive definite, no convergence).");
  module.def(
      "dlqr",
      [](py::handle A, py::handle B, py::handle Q, py::handle R, py::handle N) {
        return solve_discrete(equation("dlqr", A, B, Q, R, N));
      },
      py::arg("A"), py::arg("B"), py::arg("Q"), py::arg("R"), py::arg("N") = py::none(),
      "The infinite-horizon LQR of x[k+1] = Ax[k] + Bu[k] with cost Σ x'Qx + u'Ru + 2x'Nu: K, S, E = "
      "thetad.dlqr(A, B, Q, R[, N]) as python-control's dlqr (S the DARE's solution, E = eig(A − BK)).");
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
