#pragma once

#include <stdexcept>
#include <string>

namespace thetad {

// Every precondition violation and numerical failure in thetad throws this, with a message that
// says what failed and why, so that the command line can print one clear line.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace thetad
