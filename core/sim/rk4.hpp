#pragma once

#include <Eigen/Core>

namespace thetad::sim {

// Scratch vectors of the classical RK4 step, allocated once per run.
struct Rk4Workspace {
  Eigen::VectorXd k1, k2, k3, k4, stage;
  explicit Rk4Workspace(Eigen::Index n) : k1(n), k2(n), k3(n), k4(n), stage(n) {}
};

// One classical RK4 step of xdot = plant.f(x, u) with u held. A template, so that a final plant
// class (the helicopter) is called without virtual dispatch on the simulation's hot path.
template <class Plant>
void rk4_step(const Plant& plant, const Eigen::VectorXd& u, double dt, Rk4Workspace& w, Eigen::VectorXd& x) {
  plant.f(x, u, w.k1);
  w.stage = x + (0.5 * dt) * w.k1;
  plant.f(w.stage, u, w.k2);
  w.stage = x + (0.5 * dt) * w.k2;
  plant.f(w.stage, u, w.k3);
  w.stage = x + dt * w.k3;
  plant.f(w.stage, u, w.k4);
  x += (dt / 6.0) * (w.k1 + 2.0 * w.k2 + 2.0 * w.k3 + w.k4);
}

}  // namespace thetad::sim
