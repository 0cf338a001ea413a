#pragma once

#include <string>

#include "core/helicopter/helicopter.hpp"
#include "export/onboard/helicopter_sdc.hpp"

namespace thetad {

// The constants an exported step's helicopter_sdc() needs (export/onboard/helicopter_sdc.hpp): the
// model's parameters, its switches and the derived quantities in effect. Throws thetad::Error when
// the model is not a controller's model (wind or scaled induced velocities in its environment).
thetad_onboard::HelicopterConstants onboard_helicopter(const heli::Helicopter& model);

// The same as C++ source: `inline constexpr thetad_onboard::HelicopterConstants NAME{...};` with
// every double exact (hexadecimal floating literals).
std::string helicopter_constants_source(const thetad_onboard::HelicopterConstants& constants, const std::string& name);

}  // namespace thetad
