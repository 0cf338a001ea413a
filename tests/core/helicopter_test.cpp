#include "core/helicopter/helicopter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/core/helicopter_fixtures.hpp"
#include "core/helicopter/forces.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "tests/heap_counter.hpp"

namespace thetad::heli {
namespace {

using namespace testing;

// ||F x + B u - f||_inf / max(1, ||f||_inf): relative to the largest derivative, absolute below 1.
double exactness_error(const Helicopter& heli, const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
  Eigen::MatrixXd F(kStateDim, kStateDim), B(kStateDim, kInputDim);
  heli.sdc(x, u, F, B);
  const Eigen::VectorXd f = heli.f(x, u);
  return (F * x + B * u - f).lpNorm<Eigen::Infinity>() / std::max(1.0, f.lpNorm<Eigen::Infinity>());
}

TEST(HelicopterExactness, RandomStatesAllOptionSets) {
  for (const auto& [name, options] : option_sets()) {
    Helicopter heli(kNominal, options);
    std::mt19937_64 rng(2024);
    double worst = 0.0;
    for (int sample = 0; sample < 10000; ++sample) {
      heli.set_environment(random_environment(rng));
      const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
      worst = std::max(worst, exactness_error(heli, x, u));
    }
    EXPECT_LE(worst, 1e-12) << name;
    std::cout << "max ||Fx+Bu-f||_inf / max(1, ||f||_inf) over 1e4 samples, " << name << ": " << worst << "\n";
  }
}

TEST(HelicopterExactness, SpecialStates) {
  // theta = 0, phi = 0 exactly (sinc branch), mu = 0 (no air motion), u_a < 0 (sign(u_a) branch), tiny angles.
  Eigen::VectorXd u(kInputDim);
  u << 82.0, -0.17, 0.02, 0.01, -0.01;
  for (const auto& [name, options] : option_sets()) {
    Helicopter heli(kNominal, options);
    Eigen::VectorXd x = rest_state();
    EXPECT_LE(exactness_error(heli, x, u), 1e-15) << name << " rest";
    x[kP] = 0.3;
    x[kQ] = -0.2;
    x[kA1] = 0.01;
    x[kB1] = -0.02;
    EXPECT_LE(exactness_error(heli, x, u), 1e-14) << name << " phi = theta = 0, mu = 0";
    x[kU] = -4.0;
    x[kV] = 1.5;
    x[kW] = -0.7;
    EXPECT_LE(exactness_error(heli, x, u), 1e-14) << name << " u_a < 0";
    x[kPhi] = 3e-5;
    x[kTheta] = -2e-5;
    EXPECT_LE(exactness_error(heli, x, u), 1e-14) << name << " angles in the sinc series";
    x[kS] = 0.7;
    EXPECT_LE(exactness_error(heli, x, u), 1e-14) << name << " s != 1";
  }
}

TEST(HelicopterSdc, SincEntriesAreContinuousAtZero) {
  Helicopter heli;
  Matrix18 F;
  Matrix18x5 B;
  Vector5 u;
  u << kNominal.mass * kNominal.gravity, 0, 0, 0, 0;
  for (double angle : {0.0, 1e-9, 9.9e-5, 1.01e-4, 1e-3, 0.5}) {
    Vector18 x = Vector18::Zero();
    x[kS] = 1.0;
    x[kPhi] = angle;
    x[kTheta] = angle;
    heli.sdc(x, u, F, B);
    const double sinc = angle == 0.0 ? 1.0 : std::sin(angle) / angle;
    EXPECT_NEAR(F(kU, kTheta), -kNominal.gravity * sinc, 1e-15 * kNominal.gravity) << angle;
    EXPECT_NEAR(F(kV, kPhi), kNominal.gravity * std::cos(angle) * sinc, 1e-15 * kNominal.gravity) << angle;
  }
}

TEST(HelicopterSdc, ConstantPartOnceThenVaryingPartIsSdc) {
  // A controller's hot path: sdc_constant() once into buffers of NaN, then sdc_varying() at every
  // state writes all that sdc() writes, for every option set, so F x + B u == f holds through it.
  for (const auto& [name, options] : option_sets()) {
    Helicopter heli(kNominal, options);
    Eigen::MatrixXd F = Eigen::MatrixXd::Constant(kStateDim, kStateDim, std::numeric_limits<double>::quiet_NaN());
    Eigen::MatrixXd B = Eigen::MatrixXd::Constant(kStateDim, kInputDim, std::numeric_limits<double>::quiet_NaN());
    heli.sdc_constant(F, B);
    std::mt19937_64 rng(77);
    for (int sample = 0; sample < 1000; ++sample) {
      heli.set_environment(random_environment(rng));
      const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
      heli.sdc_varying(x, u, F, B);
      const SdcPlant::Coefficients full = heli.sdc(x, u);
      ASSERT_EQ(F, full.F) << name << ", sample " << sample;
      ASSERT_EQ(B, full.B) << name << ", sample " << sample;
      const Eigen::VectorXd f = heli.f(x, u);
      ASSERT_LE((F * x + B * u - f).lpNorm<Eigen::Infinity>() / std::max(1.0, f.lpNorm<Eigen::Infinity>()), 1e-12)
          << name << ", sample " << sample;
    }
  }
}

TEST(HelicopterSdc, SdcEqualsSdcAtTheSolvedRotorSpeed) {
  Helicopter heli;
  std::mt19937_64 rng(5);
  const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
  Matrix18 F1, F2;
  Matrix18x5 B1, B2;
  heli.sdc(x, u, F1, B1);
  heli.sdc_at_rotor_speed(x, heli.rotor_speed(x, u[kTmr]), F2, B2);
  EXPECT_EQ(F1, F2);
  EXPECT_EQ(B1, B2);
}

TEST(HelicopterSdc, HotPathAllocatesNothing) {
  // The counter works: a dynamic Eigen vector allocates.
  const long probe = thetad::testing::heap_allocations_during([] { Eigen::VectorXd v = Eigen::VectorXd::Ones(64); });
  if (probe < 0) GTEST_SKIP() << "malloc cannot be interposed in this build";
  ASSERT_GT(probe, 0);

  Helicopter heli;
  std::mt19937_64 rng(9);
  const Vector18 x = random_state(rng);
  const Vector5 u = random_input(rng);
  Vector18 xdot;
  Matrix18 F;
  Matrix18x5 B;
  Eigen::VectorXd xd(kStateDim);
  EXPECT_EQ(thetad::testing::heap_allocations_during([&] {
              heli.f(x, u, xdot);
              heli.f(x, u, xd);
              heli.sdc(x, u, F, B);
              heli.sdc_at_rotor_speed(x, 170.0, F, B);
            }),
            0);
}

TEST(HelicopterPhysics, FreeFallWithZeroThrustAcceleratesAtG) {
  // Zero thrust needs the governor (A4 has no root for T = 0); the constant induced velocities
  // would still blow on the fuselage and fin without a rotor, so they are switched off.
  ModelOptions options = ModelOptions::resolved();
  options.rotor_speed_model = ModelOptions::RotorSpeedModel::governor;
  Helicopter heli(kNominal, options);
  Environment still;
  still.induced_main_scale = 0.0;
  still.induced_tail_scale = 0.0;
  heli.set_environment(still);
  const Eigen::VectorXd xdot = heli.f(rest_state(), Eigen::VectorXd::Zero(kInputDim));
  EXPECT_EQ(xdot[kU], 0.0);
  EXPECT_EQ(xdot[kV], 0.0);
  EXPECT_EQ(xdot[kW], kNominal.gravity);
  EXPECT_EQ(xdot[kP], 0.0);
  EXPECT_EQ(xdot[kQ], 0.0);
}

TEST(HelicopterPhysics, PureYawRateLeavesPositionStill) {
  Helicopter heli;
  Eigen::VectorXd x = rest_state();
  x[kR] = 1.0;
  x[kPsi] = 0.7;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = 80.0;
  const Eigen::VectorXd xdot = heli.f(x, u);
  EXPECT_EQ(xdot.segment<3>(kXp), Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(xdot[kPsi], 1.0);
}

TEST(HelicopterPhysics, RotationMatrixIsOrthonormal) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const AirData air = air_data(Environment{}, random_state(rng));
    EXPECT_LE((air.rotation.transpose() * air.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
    EXPECT_NEAR(air.rotation.determinant(), 1.0, 1e-15);
  }
}

TEST(HelicopterPhysics, HoverThrustAndRotorSpeed) {
  // At rest the thrust holding altitude is m g plus the fuselage download (+0.32 N, A-8).
  Helicopter heli;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = 0.0;
  Eigen::VectorXd x = rest_state();
  const Forces forces = evaluate_forces(kNominal, heli.options(), heli.environment(), air_data(heli.environment(), x), x, 172.0);
  const double hover_thrust = kNominal.mass * kNominal.gravity + forces.z_fus;
  EXPECT_NEAR(hover_thrust, kNominal.mass * kNominal.gravity, 0.005 * kNominal.mass * kNominal.gravity);
  u[kTmr] = hover_thrust;
  EXPECT_NEAR(heli.f(x, u)[kW], 0.0, 1e-14);
  EXPECT_NEAR(heli.rotor_speed(x, hover_thrust), 172.0, 0.5);
}

TEST(HelicopterPhysics, AerodynamicSurfacesNeverAddEnergy) {
  // Drag and lift of the fuselage, fin, horizontal tail (resolved sign) and the tail rotor's
  // velocity force (resolved sign) all oppose the air velocity they see.
  Helicopter heli;
  std::mt19937_64 rng(11);
  for (int i = 0; i < 5000; ++i) {
    const Environment env = random_environment(rng);
    const Eigen::VectorXd x = random_state(rng);
    const AirData air = air_data(env, x);
    const Forces f = evaluate_forces(kNominal, heli.options(), env, air, x, uniform(rng, 50, 300));
    EXPECT_LE(f.x_fus * air.u_a + f.y_fus * air.v_a, 0.0);
    EXPECT_LE(f.z_fus * (air.w_a - f.induced_main), 0.0);
    EXPECT_LE(f.y_vf * (air.v_a - kNominal.eps_vf_tr * f.induced_tail - kNominal.l_tr * x[kR]), 0.0);
    EXPECT_LE(f.z_ht * (air.w_a + kNominal.l_ht * x[kQ] - f.wake_factor * f.induced_main), 0.0);
    EXPECT_LE(f.y_tr * (air.v_a - kNominal.l_tr * x[kR] + kNominal.h_tr * x[kP]), 0.0);
    // Stall clamps hold.
    const double w_ht = air.w_a + kNominal.l_ht * x[kQ] - f.wake_factor * f.induced_main;
    EXPECT_LE(std::abs(f.z_ht), 0.5 * kNominal.rho * kNominal.s_ht * (air.u_a * air.u_a + w_ht * w_ht) * (1 + 1e-15));
  }
}

TEST(HelicopterPhysics, ExplicitYawEquationSatisfiesTheImplicitOne) {
  // I_zz r_dot = p q (I_xx - I_yy) + N_vf + N_tr - Q_e - m Y_ped l_tr delta_ped with
  // Q_e = -I_rot r_dot + Q_mr + n_tr Q_tr (B1).
  Helicopter heli;
  std::mt19937_64 rng(13);
  for (int i = 0; i < 100; ++i) {
    const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
    const double r_dot = heli.f(x, u)[kR];
    const AirData air = air_data(heli.environment(), x);
    const Forces f = evaluate_forces(kNominal, heli.options(), heli.environment(), air, x, heli.rotor_speed(x, u[kTmr]));
    const double q_e = -kNominal.rotor_inertia() * r_dot + f.q_mr + kNominal.gear_tr * f.q_tr;
    const double rhs = x[kP] * x[kQ] * (kNominal.ixx - kNominal.iyy) + f.n_vf + f.n_tr - q_e -
                       kNominal.mass * kNominal.y_ped_tr * kNominal.l_tr * u[kPed];
    EXPECT_NEAR(kNominal.izz * r_dot, rhs, 1e-12 * std::max(1.0, std::abs(rhs)));
  }
}

TEST(HelicopterPhysics, WakeFactorBreakpoints) {
  // K_lambda of A1-A3 with V_imr = 4.2, w_a = 0: chi = u_a/4.2; eta_i = 0.0625, eta_f = 3.3125.
  EXPECT_NEAR(kNominal.wake_skew_start(), 0.0625, 1e-15);
  EXPECT_NEAR(kNominal.wake_skew_end(), 3.3125, 1e-15);
  const Helicopter heli;
  auto k_lambda = [&](double u_a) {
    Eigen::VectorXd x = rest_state();
    x[kU] = u_a;
    return evaluate_forces(kNominal, heli.options(), Environment{}, air_data(Environment{}, x), x, 170.0).wake_factor;
  };
  EXPECT_EQ(k_lambda(-3.0), 0.0);
  EXPECT_EQ(k_lambda(0.2), 0.0);                           // chi = 0.048 < eta_i
  EXPECT_NEAR(k_lambda(4.2), 1.5 * (1 - 0.0625) / 3.25, 1e-15);  // chi = 1
  EXPECT_EQ(k_lambda(20.0), 1.5);                          // chi = 4.76 > eta_f
}

TEST(HelicopterErrors, PitchBeyond85DegreesThrows) {
  Helicopter heli;
  Eigen::VectorXd x = rest_state();
  x[kTheta] = 86.0 * std::numbers::pi / 180.0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = 80.0;
  EXPECT_THROW(heli.f(x, u), Error);
  EXPECT_THROW(heli.sdc(x, u), Error);
  x[kTheta] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(heli.f(x, u), Error);
}

TEST(HelicopterErrors, SolverFailureAndZeroBiasStateThrow) {
  Helicopter heli;
  Eigen::VectorXd x = rest_state();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = -5.0;
  EXPECT_THROW(heli.f(x, u), Error);
  u[kTmr] = 80.0;
  x[kS] = 0.0;
  EXPECT_THROW(heli.sdc(x, u), Error);
  Matrix18 F;
  Matrix18x5 B;
  EXPECT_THROW(heli.sdc_at_rotor_speed(rest_state(), 0.0, F, B), Error);
}

TEST(HelicopterGovernor, RotorSpeedIsNominal) {
  ModelOptions options = ModelOptions::resolved();
  options.rotor_speed_model = ModelOptions::RotorSpeedModel::governor;
  const Helicopter heli(kNominal, options);
  EXPECT_EQ(heli.rotor_speed(rest_state(), 10.0), kNominal.omega_nom);
  EXPECT_EQ(heli.rotor_speed(rest_state(), -3.0), kNominal.omega_nom);
}

TEST(HelicopterDesignDefaults, ThePaperWeightsAndHoverThrust) {
  Parameters heavier = kNominal;
  heavier.mass = 9.0;
  const DesignDefaults defaults = Helicopter(heavier).design_defaults();
  EXPECT_EQ(defaults.state_weights, paper_state_weights());
  EXPECT_EQ(defaults.input_weights, paper_input_weights());
  Vector5 hover_thrust = Vector5::Zero();
  hover_thrust[kTmr] = 9.0 * kNominal.gravity;
  EXPECT_EQ(defaults.input, Eigen::VectorXd(hover_thrust));
}

TEST(ModelOptionsStrings, RoundTripAndErrors) {
  for (const auto& preset : {ModelOptions::resolved(), ModelOptions::paper()}) {
    ModelOptions parsed = ModelOptions::preset("resolved");
    for (const auto name : ModelOptions::names) parsed.set(name, preset.get(name));
    EXPECT_EQ(parsed, preset) << preset.to_string();
  }
  EXPECT_EQ(ModelOptions::preset("paper"), ModelOptions::paper());
  EXPECT_EQ(ModelOptions::resolved().get("yaw_inertia"), "minus_rotor");
  EXPECT_EQ(ModelOptions::paper().get("lateral_flap_speed_sign"), "+1");
  ModelOptions o;
  o.set("induced_velocity_model", "lambda0_omega_r");
  EXPECT_EQ(o.induced_velocity_model, ModelOptions::InducedVelocityModel::lambda0_omega_r);
  EXPECT_THROW(o.set("induced_velocity_model", "momentum"), Error);
  EXPECT_THROW(o.set("no_such_switch", "on"), Error);
  EXPECT_THROW(o.set("horizontal_tail_sign", "0"), Error);
  EXPECT_THROW(ModelOptions::preset("literal"), Error);
}

}  // namespace
}  // namespace thetad::heli
