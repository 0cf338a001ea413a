#include "core/sim/plant_simulator.hpp"

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/sim/rk4.hpp"

namespace thetad::sim {

namespace {

std::string at_time(const std::string& what, double t) {
  char text[64];
  std::snprintf(text, sizeof text, " at t = %.4f s", t);
  return what + text;
}

}  // namespace

PlantRun simulate_plant(ControlLaw& law, const SdcPlant& plant, const ReferenceTrajectory& reference,
                        const Eigen::VectorXd& x0, const SimulationSettings& settings, double max_state) {
  settings.validate();
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  if (x0.size() != n)
    throw Error("simulate_plant: x0 has " + std::to_string(x0.size()) + " entries, the plant " + std::to_string(n));
  const double period = settings.controller_period();
  const auto samples = static_cast<std::int64_t>(std::llround(settings.duration / period));
  const DesignDefaults weights = plant.design_defaults();

  PlantRun run;
  const std::int64_t rows = settings.keep_log ? (samples + settings.log_every - 1) / settings.log_every : 0;
  check_run_memory(8.0 * static_cast<double>(rows) * static_cast<double>(1 + n + m), rows);
  run.log.resize(rows, 1 + n + m);
  Eigen::VectorXd x = x0, u(m), v(n);
  Rk4Workspace workspace(n);
  PositionIntegral integral;
  double t = 0.0;
  try {
    law.reset(x0, 0.0);
  } catch (const std::exception& error) {
    run.reason = at_time(std::string("controller failed: ") + error.what(), t);
    run.status = RunStatus::failed;
  }
  for (std::int64_t k = 0; k < samples && run.reason.empty(); ++k) {
    t = static_cast<double>(k) * period;
    const Eigen::Vector3d position = reference.position(t);
    const Reference now{position, integral.value};
    try {
      law.control(t, x, now, u);
      if (!u.allFinite()) throw Error("non-finite command");
    } catch (const std::exception& error) {
      run.reason = at_time(std::string("controller failed: ") + error.what(), t);
      run.status = RunStatus::failed;
      break;
    }
    plant.tracking_vector(x, now, v);
    run.cost += 0.5 * (v.cwiseAbs2().dot(weights.state_weights) + u.cwiseAbs2().dot(weights.input_weights)) * period;
    ++run.controller_samples;
    if (settings.keep_log && k % settings.log_every == 0) run.log.row(k / settings.log_every) << t, x.transpose(), u.transpose();
    integral.accumulate(position, period);
    for (int step = 1; step <= settings.controller_period_steps && run.reason.empty(); ++step) {
      const double t_end = t + step * settings.dt;
      try {
        rk4_step(plant, u, settings.dt, workspace, x);
        if (!x.allFinite()) run.reason = at_time("non-finite state", t_end);
        else if (x.cwiseAbs().maxCoeff() > max_state) run.reason = at_time("|x| beyond " + std::to_string(max_state), t_end);
      } catch (const Error& error) {
        run.reason = at_time(std::string("plant failed: ") + error.what(), t_end);
      }
      if (!run.reason.empty()) t = t_end;
    }
  }
  if (!run.reason.empty()) {
    if (run.status != RunStatus::failed) run.status = RunStatus::diverged;
    if (settings.keep_log)
      run.log.conservativeResize((run.controller_samples + settings.log_every - 1) / settings.log_every, Eigen::NoChange);
  }
  run.end_time = run.reason.empty() ? static_cast<double>(samples) * period : t;
  run.controller_counters = law.counters();
  return run;
}

}  // namespace thetad::sim
