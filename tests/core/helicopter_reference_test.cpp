// The helicopter against the reference numbers of docs/model.md §13 (the independent check): A0
// and g0 at rest, and the hover trims of both presets.
#include "core/helicopter/helicopter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>

#include "core/error.hpp"
#include "tests/core/helicopter_fixtures.hpp"
#include "core/helicopter/forces.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad::heli {
namespace {

using namespace testing;

// docs/model.md §13: A0 = F and g0 = B at rest, s = 1, T_mr = m g, resolved preset.
TEST(HelicopterReference, RestStateA0AndG0) {
  Helicopter heli;
  const Eigen::VectorXd x = rest_state();
  const double thrust = kNominal.mass * kNominal.gravity;
  const double omega = heli.rotor_speed(x, thrust);
  EXPECT_NEAR(omega, 171.927, 5e-4);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = thrust;
  Eigen::MatrixXd F(kStateDim, kStateDim), B(kStateDim, kInputDim);
  heli.sdc(x, u, F, B);

  struct Entry {
    int row, col;  // 1-based as printed
    double value, tolerance;
  };
  const std::vector<Entry> a0 = {
      {1, 4, 1, 0},       {2, 5, 1, 0},        {3, 6, 1, 0},         {4, 8, -9.81, 0},
      {5, 7, 9.81, 0},    {5, 18, 6.3246e-6, 5e-11}, {6, 18, 9.84953, 5e-6}, {7, 10, 1, 0},
      {8, 11, 1, 0},      {9, 12, 1, 0},       {10, 14, 300, 1e-12}, {10, 18, 2.30496e-5, 5e-11},
      {11, 13, 158.824, 5e-4}, {12, 18, -36.6771, 5e-5}, {13, 11, -1, 0}, {13, 13, -10, 1e-14},
      {14, 10, -1, 0},    {14, 14, -10, 1e-14}, {15, 1, 1, 0},        {16, 2, 1, 0},
      {17, 3, 1, 0},      {18, 18, -0.1, 0}};
  const std::vector<Entry> g0 = {{5, 2, 5.4, 0},        {6, 1, -0.121951, 5e-7}, {10, 2, 19.68, 1e-12},
                                 {12, 2, -217.810, 5e-4}, {13, 4, 44.515, 5e-4},  {14, 5, 44.515, 5e-4}};
  Eigen::MatrixXd expected_F = Eigen::MatrixXd::Zero(kStateDim, kStateDim);
  Eigen::MatrixXd expected_B = Eigen::MatrixXd::Zero(kStateDim, kInputDim);
  for (const auto& e : a0) {
    EXPECT_NEAR(F(e.row - 1, e.col - 1), e.value, e.tolerance) << "A0(" << e.row << "," << e.col << ")";
    expected_F(e.row - 1, e.col - 1) = F(e.row - 1, e.col - 1);
  }
  for (const auto& e : g0) {
    EXPECT_NEAR(B(e.row - 1, e.col - 1), e.value, e.tolerance) << "g0(" << e.row << "," << e.col << ")";
    expected_B(e.row - 1, e.col - 1) = B(e.row - 1, e.col - 1);
  }
  // Every other entry is exactly zero.
  EXPECT_EQ(F, expected_F);
  EXPECT_EQ(B, expected_B);

  // Eigenvalues: 0 (x13; a Jordan chain theta -> u -> x_p -> x_i spreads them to ~eps^(1/4)),
  // -0.1, -5 +/- 16.583j, -5 +/- 11.568j.
  const Eigen::VectorXcd eigenvalues = thetad::testing::eigenvalues_of(F);
  int zeros = 0;
  std::vector<std::complex<double>> others;
  for (const auto& lambda : eigenvalues) {
    if (std::abs(lambda) < 1e-3) ++zeros;
    else others.push_back(lambda);
  }
  EXPECT_EQ(zeros, 13);
  ASSERT_EQ(others.size(), 5u);
  std::sort(others.begin(), others.end(), [](auto a, auto b) { return a.imag() < b.imag(); });
  EXPECT_NEAR(others[0].real(), -5, 1e-9);
  EXPECT_NEAR(others[0].imag(), -16.583, 5e-4);
  EXPECT_NEAR(others[1].real(), -5, 1e-9);
  EXPECT_NEAR(others[1].imag(), -11.568, 5e-4);
  EXPECT_NEAR(others[2].real(), -0.1, 1e-12);
  EXPECT_NEAR(others[2].imag(), 0, 1e-12);
  EXPECT_NEAR(others[3].imag(), 11.568, 5e-4);
  EXPECT_NEAR(others[4].imag(), 16.583, 5e-4);
}

// docs/model.md §13: the hover trim at h = 3.5 m (u = v = w = p = q = r = 0, theta = a1 = delta_lon =
// delta_col = 0). Unknowns phi, b1, T_mr, delta_ped, delta_lat; equations v_dot, w_dot, p_dot,
// r_dot, b1_dot = 0.
using TrimVector = Eigen::Matrix<double, 5, 1>;

std::pair<Eigen::VectorXd, Eigen::VectorXd> hover_state_input(const TrimVector& v) {
  Eigen::VectorXd x = rest_state(), u = Eigen::VectorXd::Zero(kInputDim);
  x[kZp] = -3.5;
  x[kPhi] = v[0];
  x[kB1] = v[1];
  u[kTmr] = v[2];
  u[kPed] = v[3];
  u[kLat] = v[4];
  return {x, u};
}

TrimVector hover_residual(const Helicopter& heli, const TrimVector& v) {
  const auto [x, u] = hover_state_input(v);
  const Eigen::VectorXd f = heli.f(x, u);
  return TrimVector(f[kV], f[kW], f[kP], f[kR], f[kB1]);
}

// Newton with a central-difference Jacobian from the printed trim.
TrimVector solve_hover_trim(const Helicopter& heli, TrimVector v) {
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix<double, 5, 5> jacobian;
    for (int j = 0; j < 5; ++j) {
      TrimVector plus = v, minus = v;
      const double h = 1e-7 * std::max(1.0, std::abs(v[j]));
      plus[j] += h;
      minus[j] -= h;
      jacobian.col(j) = (hover_residual(heli, plus) - hover_residual(heli, minus)) / (2 * h);
    }
    v -= jacobian.partialPivLu().solve(hover_residual(heli, v));
  }
  return v;
}

struct HoverReference {
  TrimVector trim;                               // printed phi, b1, T_mr, delta_ped, delta_lat
  double omega, q_mr, q_tr, c_t, c_q, z_fus;     // printed quantities
  double relative_tolerance;                     // on phi, b1, delta_lat (see check_hover)
};

void check_hover(const Helicopter& heli, const HoverReference& ref) {
  const TrimVector trim = solve_hover_trim(heli, ref.trim);
  EXPECT_LE(hover_residual(heli, trim).lpNorm<Eigen::Infinity>(), 1e-13);
  // T_mr and delta_ped agree to the printed digits. phi, b1 and delta_lat agree to 1e-4 relative
  // (2.5e-4 for the paper column) only: the printed values are not a converged trim of the printed
  // model; they leave |f| up to 1e-4 (p_dot) at the printed point, and the paper column's delta_lat
  // contradicts its own b1 and Omega by 2.1e-4 (PrintedTrimViolatesTheFlappingEquation).
  EXPECT_NEAR(trim[2], ref.trim[2], 5e-5) << "T_mr";
  EXPECT_NEAR(trim[3], ref.trim[3], 5e-7) << "delta_ped";
  for (int j : {0, 1, 4}) {
    EXPECT_NEAR(trim[j], ref.trim[j], ref.relative_tolerance * std::abs(ref.trim[j])) << "trim variable " << j;
  }

  const auto [x, u] = hover_state_input(trim);
  const double omega = heli.rotor_speed(x, u[kTmr]);
  const Forces forces = evaluate_forces(heli.parameters(), heli.options(), heli.environment(),
                                        air_data(heli.environment(), x), x, omega);
  EXPECT_NEAR(omega, ref.omega, 5e-4);
  EXPECT_NEAR(forces.q_mr, ref.q_mr, 5e-5);
  EXPECT_NEAR(forces.q_tr, ref.q_tr, 5e-6);
  EXPECT_NEAR(forces.thrust_coefficient, ref.c_t, 5e-11);
  EXPECT_NEAR(forces.torque_coefficient, ref.c_q, 5e-9);
  EXPECT_NEAR(forces.z_fus, ref.z_fus, 5e-5);
  std::cout << std::setprecision(9) << "hover trim: phi " << trim[0] << ", b1 " << trim[1] << ", T_mr " << trim[2]
            << ", delta_ped " << trim[3] << ", delta_lat " << trim[4] << "; Omega " << omega << ", Q_mr " << forces.q_mr
            << ", Q_tr " << forces.q_tr << ", C_T " << forces.thrust_coefficient << ", C_Q "
            << forces.torque_coefficient << ", Z_fus " << forces.z_fus << "; |f| at the printed trim "
            << hover_residual(heli, ref.trim).lpNorm<Eigen::Infinity>() << "\n";
}

// C_Qmr: §10.2 prints 2.0760e-4, but its own Q_mr = 6.6061 N m gives
// Q_mr/(rho (Omega R)^2 pi R^3) = 2.0762e-4, as does C_T lambda0 + C_D0 sigma/8 = 6.46866e-5 +
// 1.42933e-4 = 2.07619e-4: the printed C_Qmr is off by one in its last digit; 2.0762e-4 is used.
TEST(HelicopterReference, HoverTrimResolved) {
  check_hover(Helicopter(kNominal, ModelOptions::resolved()),
              {TrimVector(0.084647, 0.0081850, 80.4781, -0.168466, 0.0018380), 171.966, 6.6061, 0.03909, 0.0019602,
               2.0762e-4, 0.3241, 1e-4});
}

// The paper-literal column of §10.2 was computed with the computed solidity (its Q_mr = 6.5532 and
// C_Qmr need sigma = 0.047644; with the Nomenclature's 0.0361, C_Qmr = 1.7299e-4 and Q_mr = 5.46), although
// §9 defines the paper preset with solidity = nomenclature. Its Omega_mr is printed 171.277, but
// A4 in hover gives Omega = sqrt(T/(2 eta_w lambda0^2 rho pi R^4)) = 171.27644 for the printed
// T_mr = 79.8341 N (171.276 rounded): 171.2764 is used. We keep §9's preset and check the
// column with that one switch set to computed; the preset as defined is checked below.
TEST(HelicopterReference, HoverTrimPaperLiteralWithComputedSolidity) {
  ModelOptions options = ModelOptions::paper();
  options.solidity = ModelOptions::Solidity::computed;
  check_hover(Helicopter(kNominal, options),
              {TrimVector(0.084023, 0.0081360, 79.8341, -0.167118, 0.0018420), 171.2764, 6.5532, 0.03878, 0.0019602,
               2.0762e-4, -0.3241, 2.5e-4});
}

// Model-free evidence: in hover (p = v_a = 0) Eq. (6) reads b1 = B^nom (Omega/Omega_nom)^2 delta_lat.
// The printed (b1, Omega, delta_lat) of both §10.2 columns violate it by more than their rounding.
TEST(HelicopterReference, PrintedTrimViolatesTheFlappingEquation) {
  struct Column { double b1, omega, lat; };
  for (const auto& c : {Column{0.0081850, 171.966, 0.0018380}, Column{0.0081360, 171.277, 0.0018420}}) {
    const double implied_b1 = 4.2 * (c.omega / 167.0) * (c.omega / 167.0) * c.lat;
    const double rounding = 4.2 * (c.omega / 167.0) * (c.omega / 167.0) * 5e-8 + 5e-8 + 2 * implied_b1 * 5e-4 / c.omega;
    EXPECT_GT(std::abs(implied_b1 - c.b1), rounding) << "b1 " << c.b1 << " vs implied " << implied_b1;
  }
}

TEST(HelicopterReference, PaperPresetUsesNomenclatureSolidityInTheTorque) {
  const Helicopter heli(kNominal, ModelOptions::paper());
  Eigen::VectorXd x = rest_state();
  x[kZp] = -3.5;
  const double omega = heli.rotor_speed(x, 79.8341);
  const Forces forces = evaluate_forces(heli.parameters(), heli.options(), heli.environment(),
                                        air_data(heli.environment(), x), x, omega);
  // C_Q = C_T lambda0 + C_D0 sigma/8 in hover: 0.0019602 * 0.033 + 0.024 * 0.0361/8.
  EXPECT_NEAR(forces.torque_coefficient, 2 * 0.9 * 0.033 * 0.033 * 0.033 + 0.024 * 0.0361 / 8, 1e-15);
  std::cout << "paper preset (sigma = 0.0361) in hover: C_Q " << forces.torque_coefficient << ", Q_mr " << forces.q_mr
            << " (docs/model.md §13 prints 2.0760e-4, 6.5532)\n";
}

}  // namespace
}  // namespace thetad::heli
