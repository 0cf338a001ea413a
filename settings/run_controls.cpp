#include "settings/run_controls.hpp"

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "settings/run_settings.hpp"

namespace thetad {

void fly(const RunControls& controls, sim::SimulationSettings& settings) {
  for (const RunSetting& setting : run_settings()) {
    if (setting.fly) setting.fly(controls, settings);
  }
}

void apply(const RunControls& controls, sim::SimulationSettings& settings) {
  fly(controls, settings);
  // Every override given, the whole checked together (e.g. the log of a long flight must fit).
  settings.validate();
}

Eigen::VectorXd offset_initial_state(const RunControls& controls, const Eigen::VectorXd& initial_state) {
  Eigen::VectorXd x = initial_state;
  if (controls.initial_offset) {
    if (!controls.initial_offset->allFinite()) throw Error("initial_offset: every entry must be finite");
    x.segment<3>(heli::kXp) += *controls.initial_offset;
  }
  if (controls.initial_attitude_offset) {
    if (!controls.initial_attitude_offset->allFinite())
      throw Error("initial_attitude_offset: every entry must be finite");
    x.segment<3>(heli::kPhi) += *controls.initial_attitude_offset;
  }
  return x;
}

}  // namespace thetad
