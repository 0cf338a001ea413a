#pragma once

#include "controllers/registry.hpp"
#include "experiment/controller_spec.hpp"

namespace thetad {

// The controller `spec` describes, designed in `context`. Before it, every other block of the
// settings file it came from is checked (ControllerRegistry::check), so a file with a typo fails
// whichever of its controllers is flown. Errors name their source:
//  - a field error: "<file>:<line>:<column>: field '<name>': <reason>" (a SettingsError);
//  - a design failure (no stabilising CARE solution, no trim, ...): the label, the controller, the
//    settings block's file and position, and the numerical reason.
BuiltController build_controller(const ControllerSpec& spec, const ControllerContext& context);

}  // namespace thetad
