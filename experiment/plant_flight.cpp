#include "experiment/plant_flight.hpp"

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "experiment/build_info.hpp"
#include "experiment/controller_build.hpp"
#include "experiment/result_json.hpp"
#include "settings/settings.hpp"

namespace thetad {

PlantFlightResult fly_plant(const SdcPlant& plant, const ControllerSpec& spec, const Eigen::VectorXd& x0,
                            const ReferenceTrajectory& reference, const RunControls& controls) {
  if (!controls.duration) throw Error("fly_plant: the run controls must give a duration");
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  apply(controls, settings);
  settings.actuator_limits.enabled = false;  // the helicopter's servos: nothing to do with a user's plant
  const ControllerContext context(plant, x0, 0.0);
  BuiltController built = build_controller(spec, context);
  return {spec, built.settings, settings, x0, sim::simulate_plant(*built.controller, plant, reference, x0, settings)};
}

RunFiles write_plant_run_files(const PlantFlightResult& result, const std::string& plant,
                               const std::filesystem::path& folder) {
  const Eigen::MatrixXd& log = result.run.log;
  const auto n = result.initial_state.size(), m = log.cols() - 1 - n;
  LogWriter write_log;
  if (result.simulation.keep_log) {
    write_log = [&](std::ostream& out) {
      std::string header = "t_s";
      for (Eigen::Index i = 0; i < n; ++i) header += ",x_" + std::to_string(i);
      for (Eigen::Index j = 0; j < m; ++j) header += ",u_" + std::to_string(j);
      CsvStream csv(out, header);
      Eigen::VectorXd row(log.cols());
      for (Eigen::Index r = 0; r < log.rows(); ++r) {
        row = log.row(r).transpose();
        csv.row(row.data(), static_cast<std::size_t>(row.size()));
      }
      return csv.finish();
    };
  }
  return write_result_files(folder, result.spec.label, write_log, [&](const LogFile* file) {
    const sim::PlantRun& run = result.run;
    nlohmann::ordered_json j;
    j["format"] = kPlantRunFormat;
    j["label"] = result.spec.label;
    j["controller"] = result.spec.controller;
    j["controller_origin"] = ControllerRegistry::instance().origin(result.spec.controller);
    j["plant"] = plant;
    j["status"] = sim::status_name(run.status);
    j["reason"] = run.reason;
    j["end_time_s"] = run.end_time;
    j["controller_samples"] = run.controller_samples;
    j["cost"] = {{"definition", "J = 1/2 sum_k (v' Q v + u' R u) T_c, v = tracking_vector, the plant's design Q, R"},
                 {"J", run.cost}};
    nlohmann::ordered_json counters = nlohmann::ordered_json::object();
    for (const auto& [name, count] : run.controller_counters) counters[name] = count;
    j["controller_counters"] = counters;
    j["controller_settings"] = yaml_to_json(result.settings);
    j["settings_source"] = result.spec.settings_source;
    j["initial_state"] = std::vector<double>(result.initial_state.data(), result.initial_state.data() + n);
    j["settings"] = {{"dt_s", result.simulation.dt},
                     {"controller_period_s", result.simulation.controller_period()},
                     {"duration_s", result.simulation.duration},
                     {"log_every", result.simulation.log_every}};
    j["log"] = file ? nlohmann::ordered_json{{"csv", file->file}, {"sha256", file->sha256}, {"rows", file->rows}}
                    : nlohmann::ordered_json(nullptr);
    Provenance provenance;
    provenance.build = build_info();
    j["provenance"] = to_json(provenance);
    return j;
  });
}

}  // namespace thetad
