#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/control_law.hpp"

namespace thetad {

// What a controller takes from the reference beyond the commanded position (docs/model.md §7.1):
// none is the paper's tracking vector (Eq. 36: everything but the position regulated to the
// controller's own design point); velocity also regulates the plant's velocity to the commanded
// one; velocity_trim also starts from the trim of the commanded motion (state and input).
enum class FeedForward { none, velocity, velocity_trim };

// "none", "velocity", "velocity+trim": the settings' and the results' spelling.
std::string feedforward_name(FeedForward feedforward);
// Throws thetad::Error listing the three names when `name` is none of them.
FeedForward parse_feedforward(const std::string& name);
inline constexpr const char* kFeedForwardChoices[] = {"none", "velocity", "velocity+trim"};

// The steady motion a plant holds while it flies the reference at one sample: its state (every
// entry, the commanded position and integral included; the bias state 0), the input that holds
// it, and the state's rate of change along the reference. Sized by the caller (n, m, n).
struct TrimPoint {
  Eigen::VectorXd state;
  Eigen::VectorXd input;
  Eigen::VectorXd rate;
};

// Trims along a reference, designed before the flight (SdcPlant::trim_source). trim() is on the
// hot path: it writes every entry of `point` and allocates nothing; const, so that every controller
// of a comparison can share one source and fly the same trims.
class TrimSource {
 public:
  virtual ~TrimSource() = default;
  virtual void trim(const Reference& reference, TrimPoint& point) const = 0;
  // One line for the results: what the trims are and where they come from.
  virtual std::string describe() const = 0;
};

}  // namespace thetad
