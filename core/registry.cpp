#include "core/registry.hpp"

namespace thetad {

namespace {

// Function-local: registrations run during the static initialization of other files.
struct OriginState {
  std::string origin = "built-in";
  bool scoped = false;
};
OriginState& state() {
  static OriginState s;
  return s;
}

}  // namespace

RegistrationOrigin::RegistrationOrigin(std::string origin)
    : previous_(std::exchange(state().origin, std::move(origin))), previously_scoped_(std::exchange(state().scoped, true)) {}

RegistrationOrigin::~RegistrationOrigin() {
  state().origin = std::move(previous_);
  state().scoped = previously_scoped_;
}

const std::string& RegistrationOrigin::current() { return state().origin; }

bool RegistrationOrigin::scoped() { return state().scoped; }

}  // namespace thetad
