// The controllers' certificates (docs/model.md §8.4) against independent evaluations at the same
// state: the SDRE's CARE estimates and stabilizability margin, θ–D's last-term share of u.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/riccati.hpp"
#include "core/stabilizability_margin.hpp"
#include "tests/controllers/every_pass_settings.hpp"
#include "tests/controllers/scenario_one_flight.hpp"

namespace thetad {
namespace {

using testing::scenario_one_flight;

std::vector<std::string> headers(const std::vector<ControllerColumn>& columns) {
  std::vector<std::string> names;
  for (const auto& column : columns) names.push_back(column.column.header());
  return names;
}

std::vector<double> values(const Controller& controller) {
  std::vector<double> row;
  controller.log_values(row);
  return row;
}

TEST(Certificates, AreOffByDefault) {
  const auto& flight = scenario_one_flight();
  for (const char* name : {"sdre", "theta-d", "lqr", "lqr-scheduled"}) {
    const auto controller = flight.make(name, YAML::Node());
    EXPECT_TRUE(controller->log_columns().empty()) << name;
    EXPECT_TRUE(values(*controller).empty()) << name;
  }
  EXPECT_EQ(headers(flight.make("sdre", YAML::Load("{certificates: on}"))->log_columns()),
            (std::vector<std::string>{"condition_estimate", "forward_error_estimate", "stabilizability_margin"}));
  EXPECT_EQ(headers(flight.make("theta-d", YAML::Load("{certificates: on}"))->log_columns()),
            (std::vector<std::string>{"last_term_ratio"}));
  // A controller flying with feed-forward reports its inner controller's.
  EXPECT_EQ(flight.make("sdre", YAML::Load("{certificates: on, feedforward: velocity}"))->log_columns().size(),
            3u);
}

// One pass per step: each step's F, B are the SDC at its measured state and the previous step's input.
TEST(Certificates, OfTheSdreAreThoseOfADirectSolveAtTheSameState) {
  const auto& flight = scenario_one_flight();
  SdreSettings settings = testing::design_settings<SdreSettings>(flight.model);
  settings.fixed_point_iterations = 1;
  settings.certificates = true;
  SdreController sdre(flight.model, settings);
  sdre.reset(flight.scenario.initial_state, 0.0);
  Eigen::VectorXd input = settings.initial_input, u(flight.model.input_dim());
  for (std::size_t k = 0; k < flight.samples.size(); k += 250) {
    const sim::ControlSample& sample = flight.samples[k];
    const SdcPlant::Coefficients sdc = flight.model.sdc(sample.state, input);
    sdre.control(sample.t, sample.state, sample.reference, u);
    const CareResult direct =
        solve_care(sdc.F, sdc.B, settings.Q, settings.R, CareMethod::automatic, ErrorEstimates::on);
    const std::vector<double> logged = values(sdre);
    ASSERT_EQ(logged.size(), 3u);
    EXPECT_NEAR(logged[0], direct.condition, 1e-12 * direct.condition) << "t = " << sample.t;
    EXPECT_NEAR(logged[1], direct.forward_error, 1e-12) << "t = " << sample.t;
    const double margin = stabilizability_margin(sdc.F, sdc.B, settings.R);
    EXPECT_NEAR(logged[2], margin, 1e-14 * margin) << "t = " << sample.t;
    // The helicopter's positions and their integrals give zero eigenvalues: the margin is finite,
    // and positive where the SDRE solves.
    EXPECT_TRUE(std::isfinite(logged[2]) && logged[2] > 0.0) << logged[2];
    input = u;
  }
}

// The ratio ‖u_{N−1}‖_R / ‖u‖_R from the terms of value_matrix() at the same (x; input, t).
double last_term_ratio_by_terms(ThetaDController& theta_d, const SdcPlant& model, const sim::ControlSample& sample,
                                const Eigen::VectorXd& input, const Eigen::VectorXd& u) {
  Eigen::VectorXd v(model.state_dim());
  model.tracking_vector(sample.state, sample.reference, v);
  theta_d.value_matrix(sample.state, input, sample.t);
  const SdcPlant::Coefficients sdc = model.sdc(sample.state, input);
  const Eigen::MatrixXd& R = theta_d.settings().R;
  const Eigen::VectorXd last = -R.llt().solve(sdc.B.transpose() * theta_d.terms().back() * v);
  return std::sqrt(last.dot(R * last) / u.dot(R * u));
}

TEST(Certificates, OfThetaDAreItsLastTermsShareOfTheInput) {
  const auto& flight = scenario_one_flight();
  for (const int terms : {1, 2, 3}) {
    ThetaDSettings settings = testing::design_settings<ThetaDSettings>(flight.model);
    settings.terms = terms;
    settings.fixed_point_iterations = 1;
    settings.certificates = true;
    ThetaDController theta_d(flight.model, settings), reference(flight.model, settings);
    theta_d.reset(flight.scenario.initial_state, 0.0);
    reference.reset(flight.scenario.initial_state, 0.0);
    Eigen::VectorXd input = settings.initial_input, u(flight.model.input_dim());
    for (std::size_t k = 0; k < flight.samples.size(); k += 250) {
      const sim::ControlSample& sample = flight.samples[k];
      theta_d.control(sample.t, sample.state, sample.reference, u);
      const double ratio = values(theta_d).at(0);
      if (terms == 1) {
        EXPECT_DOUBLE_EQ(ratio, 1.0);  // T0 is the last term
      } else {
        const double expected = last_term_ratio_by_terms(reference, flight.model, sample, input, u);
        EXPECT_NEAR(ratio, expected, 1e-9 * expected) << "N = " << terms << ", t = " << sample.t;
      }
      input = u;
    }
  }
}

TEST(Certificates, OfThetaDShrinkWithMoreTerms) {
  // The plain series (e_i ≡ 1): each further term adds less to u, on average over the samples.
  const auto& flight = scenario_one_flight();
  double previous = INFINITY;
  for (const int terms : {2, 3, 4, 5}) {
    YAML::Node settings = YAML::Load("{certificates: on}");
    settings["terms"] = terms;
    settings["k"] = std::vector<double>(static_cast<std::size_t>(terms - 1), 0.0);
    const auto theta_d = flight.make("theta-d", settings);
    theta_d->reset(flight.scenario.initial_state, 0.0);
    Eigen::VectorXd u(flight.model.input_dim());
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < flight.samples.size(); k += 50, ++count) {
      const sim::ControlSample& sample = flight.samples[k];
      theta_d->control(sample.t, sample.state, sample.reference, u);
      sum += values(*theta_d).at(0);
    }
    const double mean = sum / count;
    EXPECT_LT(mean, previous) << "N = " << terms;
    EXPECT_GT(mean, 0.0);
    previous = mean;
  }
}

}  // namespace
}  // namespace thetad
