#pragma once

#include <string>

namespace thetad {

// A named signal with its unit: a column of a run log, a state or an input of a plant. Its CSV
// header is "name_unit", or "name" alone for a signal without a unit.
struct LogColumn {
  std::string name;
  std::string unit;
  std::string header() const { return unit.empty() ? name : name + "_" + unit; }
};

}  // namespace thetad
