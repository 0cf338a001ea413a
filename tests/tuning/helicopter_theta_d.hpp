#pragma once

// The paper's θ–D on the helicopter (registry defaults: Eqs. 33–34 weights, u0 = hover thrust) and
// states along a smooth made-up excursion: what the tuning tests evaluate the series on.

#include <cmath>
#include <memory>
#include <string>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "controllers/registry.hpp"
#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "scenarios/scenario.hpp"

namespace thetad::testing {

struct HelicopterThetaD {
  heli::Helicopter model{heli::Parameters::nominal(), heli::ModelOptions::resolved()};
  Eigen::VectorXd x0 = load_scenario(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml").initial_state;
  Eigen::VectorXd hover_input = model.design_defaults().input;

  // Reset at x0, t0 = 0; empty k, l: the paper's 1.
  ThetaDController make(int terms, const Eigen::VectorXd& k = {}, const Eigen::VectorXd& l = {}) const {
    YAML::Node node;
    node["terms"] = terms;
    for (Eigen::Index i = 0; i < k.size(); ++i) node["k"].push_back(k[i]);
    for (Eigen::Index i = 0; i < l.size(); ++i) node["l"].push_back(l[i]);
    const auto made = ControllerRegistry::instance().make("theta-d", node, ControllerContext{model, x0, 0.0});
    ThetaDController controller = dynamic_cast<const ThetaDController&>(*made);
    controller.reset(x0, 0.0);
    return controller;
  }

  // A state at time t of a 2 m/s, 0.25 rad excursion that grows in over the first seconds.
  Eigen::VectorXd excursion(double t) const {
    Eigen::VectorXd x = x0;
    const double a = 1.0 - std::exp(-t);
    x.segment(3, 3) << 2.0 * a * std::cos(0.7 * t), -1.4 * a * std::sin(0.5 * t), 0.6 * a;  // u, v, w
    x.segment(6, 3) << 0.2 * a * std::sin(0.9 * t), -0.16 * a * std::cos(0.6 * t), 0.25 * a;  // φ, θ, ψ
    x.segment(9, 3) << 0.3 * a * std::cos(1.3 * t), -0.2 * a, 0.25 * a * std::sin(t);       // p, q, r
    x.segment(12, 2) << 0.01 * a, -0.01 * a;                                                  // a1, b1
    return x;
  }
};

}  // namespace thetad::testing
