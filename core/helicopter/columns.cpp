#include "core/helicopter/helicopter.hpp"

namespace thetad::heli {

std::vector<LogColumn> Helicopter::state_columns() const {
  return {{"x_p", "m"}, {"y_p", "m"}, {"z_p", "m"},
          {"u", "m_per_s"}, {"v", "m_per_s"}, {"w", "m_per_s"},
          {"phi", "rad"}, {"theta", "rad"}, {"psi", "rad"},
          {"p", "rad_per_s"}, {"q", "rad_per_s"}, {"r", "rad_per_s"},
          {"a1", "rad"}, {"b1", "rad"},
          {"x_i", "m_s"}, {"y_i", "m_s"}, {"z_i", "m_s"},
          {"s", "unitless"}};
}

std::vector<LogColumn> Helicopter::input_columns() const {
  return {{"T_mr", "N"}, {"delta_ped", "rad"}, {"delta_col", "rad"}, {"delta_lon", "rad"}, {"delta_lat", "rad"}};
}

}  // namespace thetad::heli
