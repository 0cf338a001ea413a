#pragma once

// A per-entry objective for k_i, l_i: along a recorded SDRE trajectory, Σ_k ‖(ΣT_i(x_k, t_k; k, l)
// − P_k) ⊘ S_k‖_F², the Frobenius norm of the entrywise-scaled difference to the SDRE's P. The
// paper's σ_max fit sees only the largest eigenvalue of P, which the z-integral weight fixes; this
// one weighs every coupling the control law uses alike, in relative terms.
//
// Scale of entry (r, c) at sample k: S_rc = max(|P_rc|, floor · sqrt(P_rr P_cc)). A diagonal entry
// is compared with itself (P_rr > 0); an off-diagonal one with its own size, but never less than
// `floor` times the largest it could be (|P_rc| ≤ sqrt(P_rr P_cc) for P ⪰ 0), so that an entry
// near zero cannot dominate the sum with a relative error of a negligible coupling.

#include <Eigen/Core>

#include "controllers/theta_d.hpp"
#include "tuning/packed_series.hpp"
#include "tuning/record.hpp"
#include "tuning/search.hpp"

namespace thetad::tuning {

class EntryMatch {
 public:
  // `targets`: the packed lower triangles (pack_lower) of P at every sample of `record`, one column
  // each (sdre_value_matrices). `floor` in (0, 1]. See PackedSeries for `controller` and `threads`.
  // Throws thetad::Error when the sizes disagree, the floor is out of range or a P has a
  // diagonal entry that is not positive (naming the sample and entry).
  EntryMatch(const ThetaDController& controller, const TuningRecord& record, const Eigen::MatrixXd& targets,
             double floor, int threads);

  Eigen::Index samples() const { return series_.samples(); }
  int parameters() const { return series_.parameters(); }
  double floor() const { return floor_; }

  // Σ_k ‖(ΣT_i − P_k) ⊘ S_k‖_F² (both triangles); bit-identical for any number of threads.
  double residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const;
  // The RMS relative entry error: sqrt(residual / (samples · n²)).
  double rms_relative_error(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const;

 private:
  PackedSeries series_;
  double floor_;
  Eigen::MatrixXd targets_;  // packed P, one column per sample
  Eigen::MatrixXd weights_;  // packed (1 or 2) / S_rc²: an off-diagonal entry counts for both triangles
};

FitResult fit(const EntryMatch& match, const FitOptions& options);

}  // namespace thetad::tuning
