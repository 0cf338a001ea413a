// The feed-forward's error form (docs/model.md §7.1): F_e e + B v equals the error's true rate
// f(x, u_r + v) − ẋ_r to rounding for the helicopter, with and without trims, through both the
// one-shot sdc() and the split sdc_constant()/sdc_varying() that θ–D uses; the commanded motion's
// rate is the derivative of the commanded motion along the plant's and the reference's motion.
#include "core/error_form_plant.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "core/error.hpp"
#include "core/trim_table.hpp"
#include "tests/core/helicopter_fixtures.hpp"

namespace thetad::heli {
namespace {

using namespace testing;

// One small table for every test: speeds 0…3 m/s, four courses, level and ±0.5 m/s climbs.
std::shared_ptr<const TrimTable> small_table(const Helicopter& model) {
  static const std::shared_ptr<const TrimTable> table = std::make_shared<TrimTable>(
      model, TrimGridAxes{{0.0, 1.0, 2.0, 3.0}, {0.0, std::numbers::pi / 2, std::numbers::pi, 1.5 * std::numbers::pi},
                          {-0.5, 0.0, 0.5}, 3.5});
  return table;
}

Reference random_reference(std::mt19937_64& rng) {
  Reference reference;
  reference.position = Eigen::Vector3d(uniform(rng, -20, 20), uniform(rng, -20, 20), uniform(rng, -10, -1));
  reference.integral = Eigen::Vector3d(uniform(rng, -50, 50), uniform(rng, -50, 50), uniform(rng, -50, 50));
  reference.velocity = Eigen::Vector3d(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -0.4, 0.4));
  reference.acceleration = Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.3, 0.3));
  return reference;
}

// Near the trims: the controller's measured state (s = 1) and a decision variable of either sign.
Eigen::VectorXd random_measured(std::mt19937_64& rng) {
  Eigen::VectorXd x = random_state(rng);
  x.segment<3>(kU) *= 0.2;
  x[kS] = 1.0;
  return x;
}

Eigen::VectorXd random_decision(std::mt19937_64& rng) {
  Eigen::VectorXd v(kInputDim);
  v << uniform(rng, -20, 20), uniform(rng, -0.1, 0.1), uniform(rng, -0.05, 0.05), uniform(rng, -0.03, 0.03),
      uniform(rng, -0.03, 0.03);
  return v;
}

// ||F e + B v − (f(x, u_r + v) − ẋ_r)||_inf / max(1, ||f||_inf).
double exactness_error(const Helicopter& model, const ErrorFormPlant& form, const Eigen::VectorXd& x,
                       const Eigen::VectorXd& v, const Eigen::MatrixXd& F, const Eigen::MatrixXd& B) {
  Eigen::VectorXd e(kStateDim);
  form.tracking_vector(x, Reference{}, e);
  const Eigen::VectorXd f = model.f(x, form.motion().input + v);
  return (F * e + B * v - (f - form.motion().rate)).lpNorm<Eigen::Infinity>() /
         std::max(1.0, f.lpNorm<Eigen::Infinity>());
}

TrimPoint zeros() {
  return {Eigen::VectorXd::Zero(kStateDim), Eigen::VectorXd::Zero(kInputDim), Eigen::VectorXd::Zero(kStateDim)};
}

TEST(ErrorFormPlant, IsExactForTheHelicopterWithAndWithoutTrims) {
  const Helicopter model;
  for (const FeedForward feedforward : {FeedForward::velocity, FeedForward::velocity_trim}) {
    ErrorFormPlant form(model, feedforward, zeros(), small_table(model));
    std::mt19937_64 rng(7);
    Eigen::MatrixXd F(kStateDim, kStateDim), B(kStateDim, kInputDim);
    Eigen::MatrixXd F_split = Eigen::MatrixXd::Zero(kStateDim, kStateDim);
    Eigen::MatrixXd B_split = Eigen::MatrixXd::Zero(kStateDim, kInputDim);
    form.sdc_constant(F_split, B_split);
    double worst = 0.0, worst_split = 0.0;
    for (int sample = 0; sample < 2000; ++sample) {
      // The decision variable: the input itself without trims, its deviation from the trim's with.
      const Eigen::VectorXd x = random_measured(rng),
                            v = feedforward == FeedForward::velocity ? random_input(rng) : random_decision(rng);
      form.aim(x, random_reference(rng));
      form.sdc(x, v, F, B);
      worst = std::max(worst, exactness_error(model, form, x, v, F, B));
      // The split evaluation, into buffers that hold the last sample's: nothing accumulates.
      form.sdc_varying(x, v, F_split, B_split);
      worst_split = std::max(worst_split, exactness_error(model, form, x, v, F_split, B_split));
      ASSERT_EQ((F_split - F).cwiseAbs().maxCoeff(), 0.0) << feedforward_name(feedforward) << ", sample " << sample;
    }
    EXPECT_LE(worst, 1e-12) << feedforward_name(feedforward);
    EXPECT_LE(worst_split, 1e-12) << feedforward_name(feedforward);
    std::printf("error form, %s: max relative ||F_e e + B v - (f - x_r')|| over 2000 samples: %.2e\n",
                feedforward_name(feedforward).c_str(), worst);
  }
}

TEST(ErrorFormPlant, TheMotionsRateIsItsDerivativeAlongThePlantAndTheReference) {
  const Helicopter model;
  for (const FeedForward feedforward : {FeedForward::velocity, FeedForward::velocity_trim}) {
    ErrorFormPlant form(model, feedforward, zeros(), small_table(model));
    std::mt19937_64 rng(11);
    double worst_commanded = 0.0, worst_trimmed = 0.0;
    for (int sample = 0; sample < 200; ++sample) {
      const Eigen::VectorXd x0 = random_measured(rng), u = random_input(rng);
      const Eigen::VectorXd xdot = model.f(x0, u);
      const Reference r0 = random_reference(rng);
      // The state and the reference a short time h away, each along its own motion.
      const auto at = [&](double h) {
        Reference r = r0;
        r.position = r0.position + h * r0.velocity + 0.5 * h * h * r0.acceleration;
        r.velocity = r0.velocity + h * r0.acceleration;
        r.integral = r0.integral + h * r0.position + 0.5 * h * h * r0.velocity;
        form.aim(x0 + h * xdot, r);
        return Eigen::VectorXd(form.motion().state);
      };
      constexpr double h = 1e-5;
      const Eigen::VectorXd difference = (at(h) - at(-h)) / (2 * h);
      form.aim(x0, r0);
      const Eigen::VectorXd& rate = form.motion().rate;
      const double scale = std::max(1.0, rate.lpNorm<Eigen::Infinity>());
      for (int i = 0; i < kStateDim; ++i) {
        const bool commanded = (i >= kXp && i <= kZp) || (i >= kU && i <= kW) || (i >= kXi && i <= kZi);
        double& worst = commanded ? worst_commanded : worst_trimmed;
        worst = std::max(worst, std::abs(difference[i] - rate[i]) / scale);
      }
    }
    // The commanded entries exactly (central differences at h = 1e-5: O(h²) and rounding ~1e-10);
    // the trims' attitude and flapping by the table's own central difference (1e-3 s), close.
    EXPECT_LE(worst_commanded, 1e-7) << feedforward_name(feedforward);
    EXPECT_LE(worst_trimmed, feedforward == FeedForward::velocity ? 0.0 : 1e-3) << feedforward_name(feedforward);
    std::printf("motion rate, %s: commanded entries %.2e, trimmed entries %.2e\n", feedforward_name(feedforward).c_str(),
                worst_commanded, worst_trimmed);
  }
}

TEST(ErrorFormPlant, RefusesWhatItCannotDo) {
  const Helicopter model;
  EXPECT_THROW(ErrorFormPlant(model, FeedForward::none, zeros(), nullptr), Error);
  EXPECT_THROW(ErrorFormPlant(model, FeedForward::velocity_trim, zeros(), nullptr), Error);
  EXPECT_THROW(ErrorFormPlant(model, FeedForward::velocity, TrimPoint{}, nullptr), Error);
}

TEST(TrimTable, HoldsTheTrimsAtItsGridPointsAndCoversTheReference) {
  const Helicopter model;
  const auto table = small_table(model);
  TrimPoint point{Eigen::VectorXd(kStateDim), Eigen::VectorXd(kInputDim), Eigen::VectorXd(kStateDim)};
  Reference reference;
  reference.velocity = Eigen::Vector3d(0.0, 2.0, -0.5);  // 2 m/s to the right, climbing 0.5 m/s
  table->trim(reference, point);
  const Trim trim = find_trim(model, TrimCondition::straight(2.0, std::numbers::pi / 2, 0.5, 3.5));
  EXPECT_LE((point.input - trim.input).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LE((point.state.segment<2>(kPhi) - trim.state.segment<2>(kPhi)).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_TRUE(point.rate.isZero(0.0));  // no acceleration commanded

  const FixedPosition hold(Eigen::Vector3d(1, 2, -3));
  const TrimGridAxes axes = TrimTable::axes_covering(hold, 10.0, 0.01);
  EXPECT_EQ(axes.speeds, std::vector<double>{0.0});
  EXPECT_EQ(axes.courses.size(), 1u);
  EXPECT_EQ(axes.climb_rates, std::vector<double>{0.0});
}

}  // namespace
}  // namespace thetad::heli
