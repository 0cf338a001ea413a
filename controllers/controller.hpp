#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/control_law.hpp"
#include "core/fixed_string.hpp"

namespace thetad {

// A controller thetad can fly and compare: a ControlLaw (name, reset, a non-allocating control
// step that writes u) that can also be copied through its interface, so that `compare` and the
// tuner can fly independent copies of a configured controller.
//
// The control step receives the measured 18-state (noisy; its integral entries hold the
// integral of the measured position, s = 1) and the reference (commanded position and its
// integral); the plant's tracking_vector() turns them into what the value function acts on (V_track, Eq. 36).
class Controller : public ControlLaw {
 public:
  virtual std::unique_ptr<Controller> clone() const = 0;
};

// The base of a controller known by name: name() is Name, and register_controller<C>
// (controllers/registry.hpp) registers C under it, so that the name a run records and the name
// a user types cannot differ. A controller whose settings select a variant may override name()
// with Name plus a suffix ("sdre-warm"); the registry accepts that and nothing else.
template <FixedString Name>
class NamedController : public Controller {
 public:
  static constexpr const char* kName = Name.value;
  std::string name() const override { return kName; }
};

}  // namespace thetad
