#include "core/helicopter/uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.hpp"

namespace thetad::heli {
namespace {

const Parameters kNominal = Parameters::nominal();

TEST(Uncertainty, TableHas45EntriesIn4Plus1Categories) {
  int counts[5] = {};
  for (int i = 0; i < kUncertaintyCount; ++i) {
    const auto& entry = kUncertaintyTable[static_cast<std::size_t>(i)];
    EXPECT_EQ(entry.number, i + 1);
    EXPECT_EQ(entry.parameter != nullptr, entry.category == UncertaintyCategory::parameter) << entry.name;
    ++counts[static_cast<int>(entry.category)];
  }
  EXPECT_EQ(counts[static_cast<int>(UncertaintyCategory::measurement)], 14);
  EXPECT_EQ(counts[static_cast<int>(UncertaintyCategory::actuator)], 5);
  EXPECT_EQ(counts[static_cast<int>(UncertaintyCategory::wind_noise)], 3);
  EXPECT_EQ(counts[static_cast<int>(UncertaintyCategory::model_noise)], 2);
  EXPECT_EQ(counts[static_cast<int>(UncertaintyCategory::parameter)], kParameterUncertaintyCount);
}

TEST(Uncertainty, PercentsOfTable1) {
  // Spot checks against docs/model.md §9.1, and the sum of all 45 percents.
  EXPECT_EQ(kUncertaintyTable[21].name, "T_mr");
  EXPECT_EQ(kUncertaintyTable[21].percent, 5.0);
  EXPECT_EQ(kUncertaintyTable[28].name, "V_imr");
  EXPECT_EQ(kUncertaintyTable[28].percent, 10.0);
  EXPECT_EQ(kUncertaintyTable[33].name, "Y_ped_tr");
  EXPECT_EQ(kUncertaintyTable[33].percent, 10.0);
  double sum = 0.0;
  for (const auto& entry : kUncertaintyTable) sum += entry.percent;
  // 10 % x 3 (V_imr, V_itr, Y_ped), 1 % x 2 (eta_w, lambda0), 0.5 % x 4 (g, m, R_mr, rho), 5 % x 36.
  EXPECT_DOUBLE_EQ(sum, 30.0 + 2.0 + 2.0 + 180.0);
}

TEST(Uncertainty, NoisePercentsByChannel) {
  for (double pct : measurement_noise_percents()) EXPECT_EQ(pct, 5.0);
  for (double pct : actuator_noise_percents()) EXPECT_EQ(pct, 5.0);
  for (double pct : wind_noise_percents()) EXPECT_EQ(pct, 5.0);
  EXPECT_EQ(induced_velocity_noise_percents()[0], 10.0);
  EXPECT_EQ(induced_velocity_noise_percents()[1], 10.0);
}

TEST(Uncertainty, DrawIsReproducibleBySeedAndWithinBounds) {
  std::mt19937_64 rng_a(42), rng_b(42), rng_c(43);
  const auto a = perturbed_parameters(kNominal, rng_a);
  const auto b = perturbed_parameters(kNominal, rng_b);
  const auto c = perturbed_parameters(kNominal, rng_c);
  ASSERT_EQ(a.report.size(), 45u);
  int parameters = 0;
  bool any_differs = false;
  for (std::size_t i = 0; i < a.report.size(); ++i) {
    const auto& row = a.report[i];
    const auto& entry = kUncertaintyTable[i];
    EXPECT_EQ(row.name, entry.name);
    EXPECT_EQ(row.percent, entry.percent);
    EXPECT_EQ(row.factor, b.report[i].factor);
    if (row.factor != c.report[i].factor) any_differs = true;
    if (entry.parameter == nullptr) {
      EXPECT_TRUE(row.per_sample);
      EXPECT_EQ(row.factor, 1.0);
      continue;
    }
    ++parameters;
    EXPECT_FALSE(row.per_sample);
    EXPECT_LE(std::abs(row.xi), 1.0);
    EXPECT_LE(std::abs(row.factor - 1.0), entry.percent / 100.0 + 1e-15);
    EXPECT_DOUBLE_EQ(a.parameters.*entry.parameter, kNominal.*entry.parameter * row.factor) << entry.name;
  }
  EXPECT_EQ(parameters, 21);
  EXPECT_TRUE(any_differs);
  // Parameters outside Table 1 are exact (docs/model.md §9.1).
  EXPECT_EQ(a.parameters.s_vf, kNominal.s_vf);
  EXPECT_EQ(a.parameters.cd_x, kNominal.cd_x);
  EXPECT_EQ(a.parameters.i_beta, kNominal.i_beta);
  EXPECT_EQ(a.parameters.gear_tr, kNominal.gear_tr);
  EXPECT_EQ(a.parameters.v_imr, kNominal.v_imr);
}

TEST(Uncertainty, DrawsSpanTheInterval) {
  std::mt19937_64 rng(7);
  double lo = 1.0, hi = -1.0, sum = 0.0;
  int n = 0;
  for (int run = 0; run < 500; ++run) {
    for (const auto& row : perturbed_parameters(kNominal, rng).report) {
      if (row.per_sample) continue;
      lo = std::min(lo, row.xi);
      hi = std::max(hi, row.xi);
      sum += row.xi;
      ++n;
    }
  }
  EXPECT_LT(lo, -0.99);
  EXPECT_GT(hi, 0.99);
  EXPECT_NEAR(sum / n, 0.0, 0.03);  // 10500 draws: standard error 0.0056
}

TEST(Uncertainty, WorstCaseAndSignVector) {
  const auto worst = worst_case_parameters(kNominal);
  EXPECT_DOUBLE_EQ(worst.parameters.mass, 8.2 * 1.005);
  EXPECT_DOUBLE_EQ(worst.parameters.omega_nom, 167.0 * 1.05);
  EXPECT_DOUBLE_EQ(worst.parameters.y_ped_tr, 5.4 * 1.1);
  // Derived quantities follow: sigma from the perturbed c_mr and R_mr.
  EXPECT_DOUBLE_EQ(worst.parameters.solidity(ModelOptions::Solidity::computed),
                   2 * 0.058 * 1.05 / (std::numbers::pi * 0.775 * 1.005));
  ParameterDraw signs;
  for (std::size_t i = 0; i < signs.size(); ++i) signs[i] = i % 2 == 0 ? 1.0 : -1.0;
  const auto mixed = perturbed_parameters(kNominal, signs);
  EXPECT_DOUBLE_EQ(mixed.parameters.lift_slope_mr, 5.5 * 1.05);  // first parameter entry: +1
  EXPECT_DOUBLE_EQ(mixed.parameters.a_lon_nom, 4.2 * 0.95);      // second: -1
  signs[3] = 1.5;
  EXPECT_THROW(perturbed_parameters(kNominal, signs), Error);
}

TEST(Uncertainty, ScaleMultipliesTheBoundsOfTheSameDraw) {
  std::mt19937_64 paper_rng(5), doubled_rng(5), nominal_rng(5);
  const auto paper = perturbed_parameters(kNominal, paper_rng);
  const auto doubled = perturbed_parameters(kNominal, doubled_rng, 2.0);
  const auto nominal = perturbed_parameters(kNominal, nominal_rng, 0.0);
  for (std::size_t i = 0; i < paper.report.size(); ++i) {
    const auto& row = paper.report[i];
    EXPECT_EQ(doubled.report[i].xi, row.xi) << row.name;  // the same draw, wider bounds
    EXPECT_NEAR(doubled.report[i].factor - 1.0, 2.0 * (row.factor - 1.0), 1e-15) << row.name;
    EXPECT_EQ(nominal.report[i].factor, 1.0) << row.name;
    EXPECT_EQ(doubled.report[i].percent, row.per_sample ? row.percent : 2.0 * row.percent) << row.name;
  }
  EXPECT_EQ(nominal.parameters.mass, kNominal.mass);
  EXPECT_NE(doubled.parameters.mass, paper.parameters.mass);
  // Y_ped_tr's 10 % bound reaches a zero factor at scale 10: refused, as are negative scales.
  ParameterDraw ones;
  ones.fill(1.0);
  EXPECT_NO_THROW(perturbed_parameters(kNominal, ones, 9.5));
  EXPECT_THROW(perturbed_parameters(kNominal, ones, 10.0), Error);
  EXPECT_THROW(perturbed_parameters(kNominal, ones, -0.5), Error);
  EXPECT_THROW(check_uncertainty_scale(std::nan("")), Error);
}

}  // namespace
}  // namespace thetad::heli
