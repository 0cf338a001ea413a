#include "experiment/step_time_file.hpp"

#include <string>

#include "core/error.hpp"
#include "experiment/json_file.hpp"
#include "experiment/sha256.hpp"
#include "experiment/step_timing.hpp"

namespace thetad {

void load_step_times(const StepTimeFile& file, sim::FlightComputerSettings& computer) {
  const std::string name = file.file.string();
  const nlohmann::ordered_json bench = read_json_file(file.file);
  if (!bench.is_object() || bench.value("format", std::string()) != kBenchFormat)
    throw Error(name + ": not a thetad bench file (its \"format\" is not " + std::string(kBenchFormat) + ")");
  const int version = bench.value("format_version", 1);
  if (version > kBenchFormatVersion)
    throw Error(name + ": written by a newer thetad (format_version " + std::to_string(version) + ")");
  // format_version 1 gave nanoseconds under the statistic's own name (step_timing.hpp).
  const std::string key = version == 1 ? file.statistic + "_ns" : "step_time_" + file.statistic + "_us";
  const double to_seconds = version == 1 ? 1e-9 : 1e-6;
  if (!bench.contains("controllers") || !bench["controllers"].is_array() || bench["controllers"].empty())
    throw Error(name + ": \"controllers\" is missing or empty");
  computer.step_times.clear();
  for (const auto& controller : bench["controllers"]) {
    if (!controller.contains("label") || !controller["label"].is_string() || !controller.contains(key) ||
        !controller[key].is_number())
      throw Error(name + ": a controller without \"label\" or \"" + key + "\"");
    computer.step_times.emplace_back(controller["label"].get<std::string>(), controller[key].get<double>() * to_seconds);
  }
  computer.step_time_source = name + " (sha256 " + sha256_of_file(file.file) + ", " + file.statistic + ")";
  computer.validate();
}

}  // namespace thetad
