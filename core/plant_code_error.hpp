#pragma once

#include <string>

#include "core/error.hpp"

namespace thetad {

// A plant's code failed, not its physics: a plant written in Python raised in f() or returned a
// wrong result (python/python_plant.hpp). The simulator ends the run as failed, as for a
// controller's fault, where a plant's other errors (the helicopter's rotor speed) end it as
// diverged.
class PlantCodeError : public Error {
 public:
  explicit PlantCodeError(const std::string& what) : Error(what) {}
};

}  // namespace thetad
