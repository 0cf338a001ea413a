// A user's program against the installed thetad: a Riccati solve through thetad::core, a
// controller built by name (which only works if the self-registering controllers survived the link
// of the installed thetad::controllers), and scenario I flown with θ–D for 2 s through
// thetad::experiment from the installed scenario file (argv[1]).
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "controllers/registry.hpp"
#include "core/riccati.hpp"
#include "experiment/flight.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  Eigen::Matrix2d a{{0.0, 1.0}, {0.0, 0.0}};
  Eigen::Vector2d b{0.0, 1.0};
  const auto result = thetad::solve_care(a, b, Eigen::Matrix2d::Identity(), Eigen::Matrix<double, 1, 1>::Identity());
  // Known solution: P = [[sqrt(3), 1], [1, sqrt(3)]].
  const double error = std::abs(result.P(0, 0) - std::sqrt(3.0)) + std::abs(result.P(0, 1) - 1.0);
  std::printf("downstream: P(0,0) = %.12f, residual %.2e\n", result.P(0, 0), result.relative_residual);

  const thetad::heli::Helicopter model;
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(thetad::heli::kStateDim);
  x0(thetad::heli::kS) = 1.0;
  auto controller = thetad::ControllerRegistry::instance().make("theta-d", YAML::Node(), {model, x0, 0.0});
  controller->reset(x0, 0.0);
  Eigen::VectorXd u(thetad::heli::kInputDim);
  controller->control(0.0, x0, thetad::Reference{}, u);
  std::printf("downstream: %s at rest commands T_mr = %.3f N\n", controller->name().c_str(), u(0));

  thetad::RunControls two_seconds;
  two_seconds.duration = 2.0;
  two_seconds.summary_only = true;
  const thetad::Flight flight(argv[1], two_seconds);
  thetad::PreparedController theta_d = flight.prepare({"theta-d", "theta-d", {}, {}, {}});
  const thetad::RunResult run = flight.fly(theta_d);
  std::printf("downstream: %s on %s for 2 s: %s, %lld samples, RMS z error %.4f m\n", run.spec.label.c_str(),
              flight.scenario().name.c_str(), thetad::sim::status_name(run.summary.status),
              static_cast<long long>(run.summary.controller_samples), run.summary.rms_tracking_error.z());
  const bool flew = run.completed() && run.summary.controller_samples == 2000 && run.log.rows() == 0;
  return error < 1e-10 && std::abs(u(0) - 80.77) < 0.1 && flew ? 0 : 1;
}
