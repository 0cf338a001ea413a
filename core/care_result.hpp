#pragma once

// What every CARE solver returns (riccati.hpp, newton_kleinman.hpp).

#include <limits>

#include <Eigen/Dense>

namespace thetad {

// How a CARE solver shows that the P it returns stabilizes A − B K (the CareSolver and
// NewtonKleinmanSolver objects take it; the one-off functions use the spectrum).
enum class StabilityProof {
  // The closed-loop spectrum, at every call: CareResult::closed_loop_eigenvalues.
  spectrum,
  // LyapunovCertificate (lyapunov_certificate.hpp) when it holds, the spectrum otherwise; when it
  // held, CareResult::closed_loop_eigenvalues are NaN. For a caller that needs P and not the
  // eigenvalues, as the SDRE: it spares the warm step one Schur form per call and the cold step
  // an eigensolver (docs/riccati.md).
  lyapunov,
};

// Whether solve_care and CareSolver also estimate how accurate their P is (CareResult's
// forward_error and condition): one residual in compensated arithmetic, a Schur form of the closed
// loop and two Lyapunov solves more (docs/care-estimates.md), so off unless asked for: the SDRE's
// per-step solve does without.
enum class ErrorEstimates { off, on };

struct CareResult {
  Eigen::MatrixXd P;                         // stabilizing solution, exactly symmetric
  Eigen::MatrixXd K;                         // R⁻¹ B' P: the optimal feedback is u = −K x
  // eig(A − B K); NaN when a solver asked for StabilityProof::lyapunov proved the closed loop
  // stable without them.
  Eigen::VectorXcd closed_loop_eigenvalues;
  // ‖A'P + PA − PBR⁻¹B'P + Q‖_F / max(1, ‖Q‖_F). On ill-conditioned equations the terms of
  // the sum can be far larger than Q, and so is this number even for a backward-stable solve.
  double relative_residual;
  // Newton steps taken. solve_care: Newton refinement steps after the direct solution: in double
  // precision when that solution was not backward stable, and with the residual in compensated
  // arithmetic when CareMethod::automatic finds its terms dwarfing Q and its residual above
  // rounding level (see riccati.cpp); 0 otherwise. Newton–Kleinman: its Lyapunov solves,
  // Newton and chord steps alike, an undone chord step and the steps before a restart included.
  int iterations;
  // Inversions of the sign-function iteration that produced P; 0 when P came from the Schur
  // form or from Newton–Kleinman.
  int sign_iterations = 0;
  // With ErrorEstimates::on, else NaN (docs/care-estimates.md):
  // an estimate of ‖P − P_exact‖_F / ‖P_exact‖_F for the equation as given (its data taken as
  // exact): the Newton correction of P with the residual in compensated arithmetic, which is
  // −(P − P_exact) to first order;
  double forward_error = std::numeric_limits<double>::quiet_NaN();
  // the relative condition number of P with respect to relative perturbations of A, G = BR⁻¹B'
  // and Q, bounded as ‖Ω⁻¹‖(‖Q‖_F + 2‖A‖_F‖P‖_F + ‖G‖_F‖P‖_F²)/‖P‖_F, Ω(X) = Ac'X + XAc.
  double condition = std::numeric_limits<double>::quiet_NaN();
};

// closed_loop_eigenvalues of a result whose stability the Lyapunov certificate proved: NaN, so that
// no eigenvalue of an earlier solve is left behind; in place, so that nothing is allocated.
inline void leave_spectrum_uncomputed(CareResult& result) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  result.closed_loop_eigenvalues.setConstant({nan, nan});
}

}  // namespace thetad
