#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/error_form_plant.hpp"

namespace thetad::sim {

// Fixed weights of J_dev, whatever weights a controller flew with, and what they are.
struct DeviationWeights {
  Eigen::VectorXd state;  // diagonal of Q (n)
  Eigen::VectorXd input;  // diagonal of R (m)
  std::string name;       // for the results: where the weights come from
};

// J_dev (docs/model.md §7.2), the comparison's score: the cost of a run's deviations from the
// commanded motion and its trim, J_dev = ½ Σ_k (e_kᵀ Q e_k + (u_k − u_r,k)ᵀ R (u_k − u_r,k)) T_c
// over the controller samples, e = V − V* the true tracking vector (Eq. 36, true integral errors)
// less the tracking vector of the commanded motion with its trim (feedforward velocity+trim's x_r:
// zero position and integral errors, the commanded body velocity, the trim's attitude and flapping,
// rates zero), u the commanded input and u_r the trim's. Unlike J (Eq. 32) it does not charge a
// controller for the input that holds the trim, and every controller is scored with one Q and R.
class DeviationCost {
 public:
  // Throws thetad::Error when the plant has no bias state or the weights do not fit it.
  DeviationCost(const SdcPlant& plant, std::shared_ptr<const TrimSource> trims, DeviationWeights weights,
                double controller_period);

  // One controller sample: the true state x, the reference, the true tracking vector v at x and
  // the commanded input u. Allocates nothing.
  void add(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
           const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& u);
  // What add() subtracts at this sample: V*, the tracking vector of the commanded motion (it
  // depends on x through the attitude the commanded velocity is resolved in), and u_r. Allocates
  // nothing.
  void target(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
              Eigen::Ref<Eigen::VectorXd> tracking, Eigen::Ref<Eigen::VectorXd> input);
  double value() const { return 0.5 * sum_ * period_; }
  const DeviationWeights& weights() const { return weights_; }
  const std::shared_ptr<const TrimSource>& trims() const { return motion_.trims(); }

 private:
  ErrorFormPlant motion_;
  DeviationWeights weights_;
  double period_;
  double sum_ = 0.0;
  Eigen::VectorXd target_, error_, input_error_;
};

}  // namespace thetad::sim
