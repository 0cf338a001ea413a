#pragma once


#include <Eigen/Core>

#include "core/helicopter/parameters.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/saturation_counts.hpp"

namespace thetad::sim {

using InputVector = Eigen::Matrix<double, heli::kInputDim, 1>;

// What the servos can do: each of the five inputs [T_mr, δ_ped, δ_col, δ_lon, δ_lat] stays in
// [lower, upper] and moves at most `rate` per second. The paper has none; the simulator
// applies them to the input the plant receives (after actuator noise), so no controller is told.
struct ActuatorLimits {
  bool enabled = true;
  // Anti-windup by conditional integration, the same for every controller (docs/model.md §12): at a
  // controller sample whose applied input a magnitude bound held, the position-error integral the
  // controllers see is held (the command's integral advances by the measured position, not by the
  // command). Acts only with the limits enabled.
  bool anti_windup = true;
  InputVector lower, upper;  // N, rad, rad, rad, rad
  InputVector rate;          // N/s, rad/s, ...

  // The defaults of docs/model.md §12 for the X-Cell 60 with parameters `p`:
  //   T_mr  [0, T_max]: T_max = C_Tmax ρ π R² (Ω_nom R)² (docs/model.md §5, 213 N nominal); the rotor-speed
  //         model needs T_mr > 0 (docs/model.md §4.2), so no negative thrust.
  //   δ_col blade pitch δ_col0 + δ_col in [−6°, +10°], the X-Cell's collective range with its stock
  //         blades (Miniature Aircraft's set-up notes); δ_col0 is the A-6 trim offset.
  //   δ_ped, δ_lon, δ_lat: no published range; twice the largest |trim| of steady flight forward
  //         and rearward up to 20 m/s and in every direction up to 4 m/s (climb ±1 m/s), one bound
  //         for both cyclics: a 100 % margin over steady flight (actuator_limits.cpp says why).
  //   rates: every input crosses its full range in kFullRangeTime (a 0.1 s/60° servo over 90° of arm).
  static ActuatorLimits x_cell(const heli::Parameters& p = heli::Parameters::nominal());
  static ActuatorLimits off();

  // Throws thetad::Error naming the first channel whose bounds are not finite, not ordered, or
  // whose rate is not positive.
  void validate() const;

  static constexpr double kFullRangeTime = 0.15;  // s
};

// Applies ActuatorLimits sample by sample. The first sample after reset() is limited in magnitude
// only (the servos start where it puts them); each later one also moves at most rate · period from
// the previous applied input. Allocates nothing.
class ActuatorLimiter {
 public:
  ActuatorLimiter(const ActuatorLimits& limits, double period);

  void reset();
  // Limits `input` (5 entries) in place and counts what it changed. Off: leaves it as it is.
  void apply(Eigen::Ref<Eigen::VectorXd> input);
  // Bit k set: channel k was at a magnitude bound in the last apply(); bit k + 5: rate-limited.
  unsigned last_flags() const { return last_flags_; }
  // Whether the last apply() held a channel at a magnitude bound (not only slowed it).
  bool at_magnitude_bound() const { return (last_flags_ & ((1u << heli::kInputDim) - 1u)) != 0; }
  const SaturationCounts& counts() const { return counts_; }

 private:
  ActuatorLimits limits_;
  InputVector step_;  // rate · period
  InputVector previous_ = InputVector::Zero();
  bool first_ = true;
  unsigned last_flags_ = 0;
  SaturationCounts counts_ = SaturationCounts::none(heli::kInputDim);
};

}  // namespace thetad::sim
