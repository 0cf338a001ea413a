// On a linear plant with a position to track and a constant trim (a steady force that an input
// holds), θ–D (k = 0, three terms), the SDRE and the LQR with the same weights and feed-forward
// are one controller: F and B are constant, so θ–D's higher terms vanish and its T0 is the SDRE's
// P; with the exact trim the bias column of the error form is zero, so the LQR's gain on the
// states without the bias state is the same law (docs/model.md §7.1).
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "controllers/feedforward_controller.hpp"
#include "controllers/lqr.hpp"
#include "controllers/registry.hpp"
#include "core/riccati.hpp"

namespace thetad {
namespace {

// Two point masses in a plane, pushed by two coupled inputs against a steady force b (gravity, a
// wind): p' = v, v' = M u + b s, i' = p (the position integrals), s' = −k_s s, the bias state s
// carrying b as the helicopter's does. States [p1, p2, v1, v2, i1, i2, s].
class PushedMass final : public SdcPlant {
 public:
  static constexpr int kBias = 6;
  PushedMass() {
    M_ << 2.0, 0.5, -0.3, 1.5;
    b_ << 0.7, -9.81;
  }
  int state_dim() const override { return 7; }
  int input_dim() const override { return 2; }
  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override {
    Eigen::MatrixXd F(7, 7), B(7, 2);
    sdc(x, u, F, B);
    xdot = F * x + B * u;
  }
  void sdc(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override {
    F.setZero();
    B.setZero();
    F.block<2, 2>(0, 2).setIdentity();
    F.block<2, 1>(2, kBias) = b_;
    F.block<2, 2>(4, 0).setIdentity();
    F(kBias, kBias) = -0.1;
    B.block<2, 2>(2, 0) = M_;
  }
  void tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                       Eigen::Ref<Eigen::VectorXd> v) const override {
    v = measured;
    v.head<2>() -= reference.position.head<2>();
    v.segment<2>(4) -= reference.integral.head<2>();
    v[kBias] = 1.0;
  }
  std::vector<TrackedState> tracked_states() const override {
    return {{0, "x", {"x_c", "m"}}, {1, "y", {"y_c", "m"}}};
  }
  int bias_state() const override { return kBias; }
  void commanded_motion(const Eigen::Ref<const Eigen::VectorXd>&, const Reference& reference,
                        TrimPoint& motion) const override {
    motion.state.head<2>() = reference.position.head<2>();
    motion.state.segment<2>(2) = reference.velocity.head<2>();
    motion.state.segment<2>(4) = reference.integral.head<2>();
    motion.rate.head<2>() = reference.velocity.head<2>();
    motion.rate.segment<2>(2) = reference.acceleration.head<2>();
    motion.rate.segment<2>(4) = reference.position.head<2>();
  }
  // The input that holds b, whatever the (unaccelerated) motion.
  Eigen::VectorXd trim_input() const { return -M_.inverse() * b_; }
  std::shared_ptr<const TrimSource> trim_source(const ReferenceTrajectory&, double, double) const override {
    class Constant final : public TrimSource {
     public:
      explicit Constant(Eigen::VectorXd input) : input_(std::move(input)) {}
      void trim(const Reference&, TrimPoint& point) const override {
        point.state.setZero();
        point.input = input_;
        point.rate.setZero();
      }
      std::string describe() const override { return "the constant trim of the pushed mass"; }

     private:
      Eigen::VectorXd input_;
    };
    return std::make_shared<Constant>(trim_input());
  }
  DesignDefaults design_defaults() const override {
    Eigen::VectorXd q(7);
    q << 40, 10, 3, 2, 5, 1, 0;
    return {q, Eigen::Vector2d(0.5, 2.0), trim_input()};
  }

 private:
  Eigen::Matrix2d M_;
  Eigen::Vector2d b_;
};

// A straight leg at constant velocity: the trim holds it exactly.
class Leg final : public ReferenceTrajectory {
 public:
  Eigen::Vector3d position(double t) const override { return Eigen::Vector3d(1.0 + 2.0 * t, -0.5 - 1.0 * t, 0.0); }
  Eigen::Vector3d velocity(double) const override { return Eigen::Vector3d(2.0, -1.0, 0.0); }
  Eigen::Vector3d acceleration(double) const override { return Eigen::Vector3d::Zero(); }
};

std::unique_ptr<Controller> build(const std::string& name, const YAML::Node& settings, const PushedMass& plant,
                                  const Eigen::VectorXd& x0, const Leg& leg) {
  ControllerContext context(plant, x0);
  context.reference = &leg;
  context.duration = 5.0;
  context.controller_period = 0.01;
  return ControllerRegistry::instance().make(name, settings, context);
}

// The LQR of lqr.hpp on the plant's states without s, flown on the same error form.
std::unique_ptr<Controller> lqr(const PushedMass& plant, const Leg& leg, FeedForward feedforward) {
  const DesignDefaults defaults = plant.design_defaults();
  Eigen::MatrixXd F(7, 7), B(7, 2);
  plant.sdc(Eigen::VectorXd::Zero(7), defaults.input, F, B);
  const CareResult design =
      solve_care(F.topLeftCorner(6, 6), B.topRows(6), defaults.state_weights.head(6).asDiagonal().toDenseMatrix(),
                 defaults.input_weights.asDiagonal().toDenseMatrix());
  const TrimPoint trim{Eigen::VectorXd::Zero(7), plant.trim_input(), Eigen::VectorXd::Zero(7)};
  const OperatingPoint on_error{Eigen::VectorXd::Zero(7), Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(7)};
  return std::make_unique<FeedForwardController>(
      ErrorFormPlant(plant, feedforward, trim, plant.trim_source(leg, 5.0, 0.01)),
      [on_error, design](const SdcPlant& form) { return std::make_unique<LqrController>(form, on_error, design, 6); });
}

// θ–D with k = 0 and three terms, and the cold SDRE (no Newton tolerance), by the registry, reset
// at rest at the origin.
std::vector<std::unique_ptr<Controller>> theta_d_and_sdre(const PushedMass& plant, const Leg& leg,
                                                          const Eigen::VectorXd& x0, const char* feedforward) {
  YAML::Node theta_d, sdre;
  theta_d["terms"] = 3;
  theta_d["k"] = std::vector<double>{0.0, 0.0};
  theta_d["feedforward"] = feedforward;
  sdre["mode"] = "cold";
  sdre["feedforward"] = feedforward;
  std::vector<std::unique_ptr<Controller>> controllers;
  controllers.push_back(build("theta-d", theta_d, plant, x0, leg));
  controllers.push_back(build("sdre", sdre, plant, x0, leg));
  for (auto& controller : controllers) controller->reset(x0, 0.0);
  return controllers;
}

Eigen::VectorXd at_rest() {
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(7);
  x0[PushedMass::kBias] = 1.0;
  return x0;
}

TEST(FeedForwardOnALinearPlant, ThetaDSdreAndLqrGiveTheSameControl) {
  const PushedMass plant;
  const Leg leg;
  std::vector<std::unique_ptr<Controller>> controllers = theta_d_and_sdre(plant, leg, at_rest(), "velocity+trim");
  controllers.push_back(lqr(plant, leg, FeedForward::velocity_trim));
  controllers.back()->reset(at_rest(), 0.0);

  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  double worst = 0.0;
  for (int sample = 0; sample < 50; ++sample) {
    const double t = 0.1 * sample;
    Reference reference{leg.position(t), Eigen::Vector3d(t + t * t, -0.5 * t - 0.5 * t * t, 0.0), leg.velocity(t),
                        leg.acceleration(t)};
    Eigen::VectorXd measured(7);
    for (int i = 0; i < 6; ++i) measured[i] = normal(rng);
    measured[PushedMass::kBias] = 1.0;
    Eigen::VectorXd u[3] = {Eigen::VectorXd(2), Eigen::VectorXd(2), Eigen::VectorXd(2)};
    for (int c = 0; c < 3; ++c) controllers[static_cast<std::size_t>(c)]->control(t, measured, reference, u[c]);
    for (int c = 1; c < 3; ++c) worst = std::max(worst, (u[c] - u[0]).norm() / u[0].norm());
  }
  std::printf("theta-d, sdre, lqr with velocity+trim on the pushed mass: max relative difference %.2e\n", worst);
  EXPECT_LE(worst, 1e-10);

  // On the commanded motion each applies the trim's input: the error is zero and so is the bias
  // column (the trim is exact).
  const double t = 2.0;
  const Reference on{leg.position(t), Eigen::Vector3d(t + t * t, -0.5 * t - 0.5 * t * t, 0.0), leg.velocity(t),
                     leg.acceleration(t)};
  Eigen::VectorXd measured(7), u(2);
  measured << on.position.head<2>(), on.velocity.head<2>(), on.integral.head<2>(), 1.0;
  for (auto& controller : controllers) {
    controller->control(t, measured, on, u);
    EXPECT_LE((u - plant.trim_input()).norm(), 1e-12 * plant.trim_input().norm()) << controller->name();
  }
}

TEST(FeedForwardOnALinearPlant, ThetaDAndSdreAgreeWithVelocityAlone) {
  const PushedMass plant;
  const Leg leg;
  const auto controllers = theta_d_and_sdre(plant, leg, at_rest(), "velocity");
  Eigen::VectorXd measured = at_rest(), ua(2), ub(2);
  measured.head<6>() << 0.3, -0.2, 1.0, 0.5, 0.1, 0.0;
  const Reference reference{leg.position(1.0), Eigen::Vector3d::Zero(), leg.velocity(1.0), leg.acceleration(1.0)};
  controllers[0]->control(1.0, measured, reference, ua);
  controllers[1]->control(1.0, measured, reference, ub);
  EXPECT_LE((ua - ub).norm() / ua.norm(), 1e-10);
}

}  // namespace
}  // namespace thetad
