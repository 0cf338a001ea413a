#include "core/helicopter/helicopter.hpp"

namespace thetad::heli {

// Position errors, the 11 body/attitude/rate/flapping states as measured, integral errors and
// s = 1 (Eq. 36, spec §7.3). The measured state's integral entries hold the integral of the
// measured position, so their difference from the reference integral is the integral error.
void Helicopter::tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured,
                                 const Reference& reference, Eigen::Ref<Eigen::VectorXd> v) const {
  v.segment<3>(kXp) = measured.segment<3>(kXp) - reference.position;
  v.segment<11>(kU) = measured.segment<11>(kU);
  v.segment<3>(kXi) = measured.segment<3>(kXi) - reference.integral;
  v(kS) = 1.0;
}

}  // namespace thetad::heli
