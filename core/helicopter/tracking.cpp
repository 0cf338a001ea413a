#include <Eigen/Geometry>

#include "core/helicopter/forces.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad::heli {

// Position errors, the 11 body/attitude/rate/flapping states as measured, integral errors and
// s = 1 (Eq. 36, docs/model.md §7). The measured state's integral entries hold the integral of the
// measured position, so their difference from the reference integral is the integral error.
void Helicopter::tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured,
                                 const Reference& reference, Eigen::Ref<Eigen::VectorXd> v) const {
  v.segment<3>(kXp) = measured.segment<3>(kXp) - reference.position;
  v.segment<11>(kU) = measured.segment<11>(kU);
  v.segment<3>(kXi) = measured.segment<3>(kXi) - reference.integral;
  v(kS) = 1.0;
}

void Helicopter::true_tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
                                      const Eigen::Vector3d& error_integral, Eigen::Ref<Eigen::VectorXd> v) const {
  v.segment<3>(kXp) = x.segment<3>(kXp) - reference.position;
  v.segment<11>(kU) = x.segment<11>(kU);
  v.segment<3>(kXi) = error_integral;
  v(kS) = 1.0;
}

std::vector<TrackedState> Helicopter::tracked_states() const {
  return {{kXp, "x", {"x_c", "m"}}, {kYp, "y", {"y_c", "m"}}, {kZp, "z", {"z_c", "m"}}};
}

}  // namespace thetad::heli

namespace thetad::heli {

// The commanded velocity is held in the body frame of the measured attitude, b = R(Θ)ᵀ v_c, so the
// velocity error u − b is the inertial velocity error seen from the body; its rate
// Rᵀ a_c − ω × b follows from Ṙ = R [ω]× (docs/model.md §7.1).
void Helicopter::commanded_motion(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                                  TrimPoint& motion) const {
  const Eigen::Matrix3d rotation = air_data(environment(), measured).rotation;
  const Eigen::Vector3d body_velocity = rotation.transpose() * reference.velocity;
  const Eigen::Vector3d rates = measured.segment<3>(kP);
  motion.state.segment<3>(kXp) = reference.position;
  motion.state.segment<3>(kU) = body_velocity;
  motion.state.segment<3>(kXi) = reference.integral;
  motion.rate.segment<3>(kXp) = reference.velocity;
  motion.rate.segment<3>(kU) = rotation.transpose() * reference.acceleration - rates.cross(body_velocity);
  motion.rate.segment<3>(kXi) = reference.position;
}

}  // namespace thetad::heli
