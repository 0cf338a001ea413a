#pragma once

// How well the θ–D series approximates the SDRE along a flight (docs/reproduction.md): at every
// kept sample of an SDRE flight, the relative error of ΣT_i against the SDRE's P (Frobenius and
// σ_max, both at the SDRE's (x_k; u_k)) and of the θ–D's control, computed in the SDRE's place
// from the same measurement and reference, against the SDRE's control.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "tuning/record.hpp"

namespace thetad::tuning {

struct ApproximationError {
  std::vector<double> time;   // t_k (s)
  Eigen::VectorXd frobenius;  // ‖ΣT_i − P‖_F / ‖P‖_F
  Eigen::VectorXd sigma;      // |σ_max(ΣT_i) − σ_max(P)| / σ_max(P)
  // ‖u_θD − u_SDRE‖_R / ‖u_SDRE‖_R with ‖u‖_R² = uᵀ R u: the cost's own measure of an input,
  // which puts thrust (N) and angles (rad) on one scale.
  Eigen::VectorXd control;
  Eigen::MatrixXd sdre_inputs, theta_d_inputs;  // m × K
};

// The errors at every sample of `record`, which must hold the θ–D's inputs as its shadow inputs
// (record_sdre_flight with the θ–D as shadow). `theta_d` reset at the flight's start; ΣT_i and P
// by cold solves on `threads` threads. Throws thetad::Error without shadow inputs or when a
// solve fails.
ApproximationError approximation_error(const SdreController& sdre, const ThetaDController& theta_d,
                                       const TuningRecord& record, int threads);

// t_s, the three relative errors, u_sdre_0.., u_theta_d_0.. per sample (%.10g).
std::string approximation_csv(const ApproximationError& error);
// {"samples": K, "frobenius": {"median", "p90", "max"}, "sigma": {...}, "control": {...}}; the
// quantiles are linear (numpy's default).
nlohmann::ordered_json approximation_summary(const ApproximationError& error);

}  // namespace thetad::tuning
