// The exported step's helicopter (export/onboard/helicopter_sdc.hpp, a second implementation of
// core/helicopter in standard C++) against the library's F(x; u), B(x; u) on random states of the
// test envelope, for every model option set, in double (to rounding) and in float.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "export/helicopter_constants.hpp"
#include "export/onboard/helicopter_sdc.hpp"
#include "tests/core/helicopter_fixtures.hpp"

namespace thetad::heli::testing {
namespace {

using thetad_onboard::Status;

// The largest difference of `onboard` (row-major) from `library`, relative to max(1, |entry|).
template <class T>
double largest_difference(const T* onboard, const Eigen::MatrixXd& library) {
  double worst = 0.0;
  for (Eigen::Index r = 0; r < library.rows(); ++r)
    for (Eigen::Index c = 0; c < library.cols(); ++c)
      worst = std::max(worst, std::abs(static_cast<double>(onboard[r * library.cols() + c]) - library(r, c)) /
                                  std::max(1.0, std::abs(library(r, c))));
  return worst;
}

TEST(OnboardHelicopter, EqualsTheLibrarysSdcOnRandomStates) {
  std::mt19937_64 rng(36);
  for (const NamedOptions& set : option_sets()) {
    const Helicopter model(kNominal, set.options);
    const thetad_onboard::HelicopterConstants constants = onboard_helicopter(model);
    double worst_double = 0.0, worst_float = 0.0;
    for (int sample = 0; sample < 300; ++sample) {
      const Eigen::VectorXd x = random_state(rng);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
      u[kTmr] = kNominal.mass * kNominal.gravity * uniform(rng, 0.5, 1.5);
      const SdcPlant::Coefficients library = model.sdc(x, u);
      double F[kStateDim * kStateDim], B[kStateDim * kInputDim];
      ASSERT_EQ(thetad_onboard::helicopter_sdc(constants, x.data(), u[kTmr], F, B), Status::ok) << set.name;
      worst_double = std::max({worst_double, largest_difference(F, library.F), largest_difference(B, library.B)});
      float xf[kStateDim], Ff[kStateDim * kStateDim], Bf[kStateDim * kInputDim];
      for (int i = 0; i < kStateDim; ++i) xf[i] = static_cast<float>(x[i]);
      ASSERT_EQ(thetad_onboard::helicopter_sdc(constants, xf, static_cast<float>(u[kTmr]), Ff, Bf), Status::ok);
      worst_float = std::max({worst_float, largest_difference(Ff, library.F), largest_difference(Bf, library.B)});
    }
    EXPECT_LT(worst_double, 1e-14) << set.name;
    EXPECT_LT(worst_float, 1e-4) << set.name;  // float inputs and arithmetic: measured up to 2.2e-5
    std::printf("%s: largest difference double %.3g, float %.3g\n", set.name.c_str(), worst_double, worst_float);
  }
}

TEST(OnboardHelicopter, ReportsTheLibrarysErrorsAsStatuses) {
  const Helicopter model;
  const thetad_onboard::HelicopterConstants constants = onboard_helicopter(model);
  double F[kStateDim * kStateDim], B[kStateDim * kInputDim];
  Eigen::VectorXd x = rest_state();
  const double hover = kNominal.mass * kNominal.gravity;
  x[kTheta] = 1.6;  // beyond 85 deg
  EXPECT_EQ(thetad_onboard::helicopter_sdc(constants, x.data(), hover, F, B), Status::pitch_beyond_limit);
  x = rest_state();
  x[kS] = 0.0;
  EXPECT_EQ(thetad_onboard::helicopter_sdc(constants, x.data(), hover, F, B), Status::bias_state_zero);
  x = rest_state();
  EXPECT_EQ(thetad_onboard::helicopter_sdc(constants, x.data(), -1.0, F, B), Status::invalid_thrust);
  EXPECT_EQ(thetad_onboard::helicopter_sdc(constants, x.data(), 1e6, F, B), Status::no_rotor_speed);
  EXPECT_THROW(model.rotor_speed(x, 1e6), Error);
}

TEST(OnboardHelicopter, RefusesAModelWithWind) {
  Helicopter model;
  Environment windy;
  windy.wind_ned.x() = 3.0;
  model.set_environment(windy);
  EXPECT_THROW(onboard_helicopter(model), Error);
}

}  // namespace
}  // namespace thetad::heli::testing
