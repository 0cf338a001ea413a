#pragma once

// The closed-loop check every helicopter controller test runs: start at the hover trim at 3.5 m
// displaced by 1 m, ask for the trim position, fly the ideal simulation (no uncertainty, wind or
// noise; RK4 1 ms, controller every step) and measure how the position error settles.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "core/trim.hpp"

namespace thetad::testing {

inline const Trim& hover_trim_at_3_5_m() {
  static const Trim trim = find_trim(heli::Helicopter(), TrimCondition::hover(3.5));
  return trim;
}

struct HoverRecovery {
  sim::RunStatus status = sim::RunStatus::completed;
  std::string reason;
  double max_error = 0.0;       // max ‖position error‖ over the run (m)
  double final_error = 0.0;     // ‖position error‖ at the end (m)
  double settle_band = 0.0;     // (m)
  double settling_time = 0.0;   // last time ‖position error‖ was above settle_band (s)
  double wall_seconds = 0.0;
};

inline std::size_t log_column(const std::string& name) {
  const auto& schema = sim::helicopter_log_schema();
  for (std::size_t i = 0; i < schema.size(); ++i) {
    if (schema[i].name == name) return i;
  }
  throw Error("no log column " + name);
}

inline HoverRecovery recover_hover(ControlLaw& law, const Eigen::Vector3d& offset, double duration,
                                   double settle_band = 0.05) {
  const Trim& hover = hover_trim_at_3_5_m();
  Eigen::VectorXd x0 = hover.state;
  x0.segment<3>(heli::kXp) += offset;
  const FixedPosition reference(hover.state.segment<3>(heli::kXp));
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  settings.duration = duration;
  settings.measure_compute_time = false;

  const auto start = std::chrono::steady_clock::now();
  const sim::RunResult run = sim::simulate(law, reference, x0, settings);
  HoverRecovery result;
  result.settle_band = settle_band;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.status = run.summary.status;
  result.reason = run.summary.reason;
  const std::size_t t = log_column("t"), xc = log_column("x_c"), xp = log_column("x_p");
  for (Eigen::Index i = 0; i < run.log.rows(); ++i) {
    const auto row = run.log.row(i);
    const double error = (row.segment<3>(static_cast<Eigen::Index>(xp)) -
                          row.segment<3>(static_cast<Eigen::Index>(xc))).norm();
    result.max_error = std::max(result.max_error, error);
    result.final_error = error;
    if (error > settle_band) result.settling_time = row(static_cast<Eigen::Index>(t));
  }
  return result;
}

inline void print(const std::string& what, const HoverRecovery& r) {
  std::printf("%s: settling (to %.3g m) %.2f s, max error %.3f m, final error %.2e m, wall %.2f s\n", what.c_str(),
              r.settle_band, r.settling_time, r.max_error, r.final_error, r.wall_seconds);
}

}  // namespace thetad::testing
