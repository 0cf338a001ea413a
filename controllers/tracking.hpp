#pragma once

#include <Eigen/Core>

#include "core/helicopter/state.hpp"
#include "core/sim/control_law.hpp"

namespace thetad {

// V_track of Eq. (36): position errors, the 11 body/attitude/rate/flapping states as measured,
// integral errors, and s = 1 (spec §7.3). Writes all 18 entries of v.
inline void tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const sim::Reference& reference,
                            Eigen::Ref<Eigen::VectorXd> v) {
  using namespace heli;
  v.segment<3>(kXp) = measured.segment<3>(kXp) - reference.position;
  v.segment<11>(kU) = measured.segment<11>(kU);
  v.segment<3>(kXi) = measured.segment<3>(kXi) - reference.integral;
  v(kS) = 1.0;
}

}  // namespace thetad
