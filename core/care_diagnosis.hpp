#pragma once

#include <string>

#include <Eigen/Core>

#include "core/error.hpp"

namespace thetad {

// Where a stabilizing solution puts the closed loop's eigenvalues: the open left half-plane (CARE)
// or the open unit disc (DARE, dare.hpp).
enum class TimeDomain { continuous, discrete };

// Which precondition of a stabilizing Riccati solution the data break, by the Popov–Belevitch–Hautus
// tests: a mode of A outside the stable region that B cannot reach ("the pair (A, B) is not
// stabilizable: the mode λ = ... is not controllable (σ_min[A − λI, B] = ...)"), or a mode on its
// boundary (the imaginary axis, the unit circle) that Q does not see ("(Q, A) is not detectable:
// ..."). "" when neither is found (then the equation is only too ill-conditioned). B and Q are
// scaled to ‖A‖_F first, so the answer does not depend on the size of the weights (tested from
// 1e-170 to 1e200). For the failure path of a solve: it costs an eigensolver and one SVD per
// suspect mode.
std::string broken_riccati_precondition(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B,
                                        const Eigen::Ref<const Eigen::MatrixXd>& Q, TimeDomain domain);

// broken_riccati_precondition of A'P + PA − PBR⁻¹B'P + Q = 0.
std::string broken_care_precondition(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::MatrixXd>& B,
                                     const Eigen::Ref<const Eigen::MatrixXd>& Q);

// For the catch block of a CARE solver: throws `error` again, with the precondition the data break
// (broken_care_precondition) in front when one is found, in place of the solver's generic hint.
[[noreturn]] void rethrow_with_diagnosis(const Error& error, const Eigen::Ref<const Eigen::MatrixXd>& A,
                                         const Eigen::Ref<const Eigen::MatrixXd>& B,
                                         const Eigen::Ref<const Eigen::MatrixXd>& Q);

}  // namespace thetad
