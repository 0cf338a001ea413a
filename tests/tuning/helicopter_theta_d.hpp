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
#include "tuning/packed_series.hpp"
#include "tuning/record.hpp"
#include "tuning/sigma_fit.hpp"

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

// 200 samples at 50 Hz along the excursion at hover input whose targets are the θ–D's own value
// matrices at known k, l (by value_matrix, the flown code, not by the expansion the fits use): σ_max
// in the record, the packed matrices in `packed` (P of the entry fit). A fit must find k, l again.
struct ThetaDTargets {
  tuning::TuningRecord record;
  Eigen::MatrixXd packed;
};

inline ThetaDTargets theta_d_targets(const HelicopterThetaD& heli, const Eigen::VectorXd& k, const Eigen::VectorXd& l) {
  ThetaDController truth = heli.make(3, k, l);
  ThetaDTargets targets;
  tuning::TuningRecord& record = targets.record;
  record.scenario = "synthetic";
  const int K = 200, n = heli.model.state_dim();
  record.states.resize(n, K);
  record.inputs.resize(heli.model.input_dim(), K);
  record.sigma_sdre.resize(K);
  targets.packed.resize(n * (n + 1) / 2, K);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(n);
  for (int i = 0; i < K; ++i) {
    const double t = 0.02 * i;
    record.time.push_back(t);
    record.states.col(i) = heli.excursion(t);
    record.inputs.col(i) = heli.hover_input;
    const Eigen::MatrixXd P = truth.value_matrix(record.states.col(i), heli.hover_input, t);
    record.sigma_sdre[i] = tuning::sigma_max_symmetric(solver, P);
    tuning::pack_lower(P, targets.packed.col(i).data());
  }
  return targets;
}

}  // namespace thetad::testing
