#include "export/controller_export.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "controllers/feedforward_controller.hpp"
#include "core/error.hpp"
#include "experiment/build_info.hpp"
#include "experiment/step_timing.hpp"
#include "export/design_export.hpp"
#include "export/helicopter_constants.hpp"
#include "export/onboard_sources.hpp"

namespace thetad {

namespace {

ExportedDesign design_of(const Controller& controller, const YAML::Node& settings, const std::string& label) {
  if (const auto* theta_d = dynamic_cast<const ThetaDController*>(&controller)) return theta_d_design(*theta_d, false);
  if (const auto* sdre = dynamic_cast<const SdreController*>(&controller)) return sdre_design(*sdre);
  if (const auto* lqr = dynamic_cast<const LqrController*>(&controller)) {
    const std::vector<double> r = settings["R"].as<std::vector<double>>();
    return lqr_design(*lqr, Eigen::VectorXd::Map(r.data(), static_cast<Eigen::Index>(r.size())).asDiagonal());
  }
  if (const auto* feedforward = dynamic_cast<const FeedForwardController*>(&controller)) {
    const auto* theta_d = dynamic_cast<const ThetaDController*>(&feedforward->inner());
    if (theta_d && feedforward->error_form().feedforward() == FeedForward::velocity) return theta_d_design(*theta_d, true);
  }
  throw Error("export: " + label + " (" + controller.name() + ", feedforward " +
              settings["feedforward"].as<std::string>("none") +
              ") is not exportable: export writes theta-d with feedforward none or velocity, lqr with feedforward none and "
              "sdre in mode capped with feedforward none");
}

// Each line of `text` as a comment line.
std::string commented(const std::string& text) {
  std::istringstream lines(text);
  std::string s, line;
  while (std::getline(lines, line)) s += "//   " + line + "\n";
  return s;
}

std::string header_of(const Flight& flight, const PreparedController& prepared, const ExportedController& exported,
                      const ExportedDesign& design) {
  YAML::Emitter settings;
  settings << YAML::Flow << prepared.settings;
  std::string s = "// " + exported.header_file + ": the " + exported.controller + " controller \"" + exported.label +
                  "\" exported by " + version_line() + ",\n// designed at the initial state of " +
                  flight.scenario().name + " (t0 = 0) with the settings\n" + commented(settings.c_str()) +
                  "// and the model options " + flight.model().options().to_string() +
                  ".\n// Standard C++20 only: no heap, no exceptions, no RTTI; the step and its data are templates over\n"
                  "// the scalar type (double, float). How to use and check it: docs/onboard.md.\n#pragma once\n\n";
  for (const char* file : {"helicopter_sdc.hpp", "step_common.hpp"}) s += onboard_source_inline(file) + "\n";
  for (const std::string& file : design.step_files) s += onboard_source_inline(file) + "\n";
  s += "namespace " + exported.name_space + " {\n\n";
  s += "inline constexpr const char* kLabel = \"" + exported.label + "\";\n";
  s += "inline constexpr const char* kController = \"" + exported.controller + "\";\n";
  s += "// R: the weights by which the check measures differences of u (‖R^{1/2} d‖).\n";
  s += "inline constexpr double kInputWeights[" + std::to_string(design.input_weights.size()) + "] = {" +
       literal_list(row_major(design.input_weights), "", "") + "\n};\n\n";
  s += helicopter_constants_source(onboard_helicopter(flight.model()), "kHelicopter") + "\n";
  s += design.data.source("Design") + "\n" + design.wrappers + "\n}  // namespace " + exported.name_space + "\n";
  return s;
}

// The first sample of each of `segments` runs of `per` samples, spread evenly over `count`.
std::vector<std::size_t> segment_starts(std::size_t count, const ExportCheckOptions& options) {
  const auto per = std::min(count, static_cast<std::size_t>(options.samples_per_segment));
  const auto segments = std::max<std::size_t>(1, std::min(static_cast<std::size_t>(options.segments), count / per));
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < segments; ++k) starts.push_back(segments == 1 ? 0 : k * (count - per) / (segments - 1));
  return starts;
}

std::string rows_of(const char* name, const std::vector<std::vector<double>>& rows) {
  std::string s = "inline constexpr double " + std::string(name) + "[" + std::to_string(rows.size()) + "][" +
                  std::to_string(rows.front().size()) + "] = {";
  for (const auto& row : rows) s += "\n    {" + literal_list(row, "", "", 6) + "},";
  return s + "\n};\n";
}

std::vector<double> reference_row(const Reference& r) {
  std::vector<double> row;
  for (const Eigen::Vector3d* part : {&r.position, &r.integral, &r.velocity, &r.acceleration})
    row.insert(row.end(), part->data(), part->data() + 3);
  return row;
}

// The recorded flight's samples of the check segments with the library's u on them: the library's
// controller fed every sample in order from its reset, as the flight fed it.
std::string check_data_of(const Flight& flight, PreparedController& prepared, const ExportedDesign& design,
                          const ExportCheckOptions& options, ExportedController& exported) {
  RecordedSamples samples = record_samples(flight, prepared);
  if (samples.status != sim::RunStatus::completed) exported.recording_diverged = samples.reason;
  const std::unique_ptr<Controller> library = prepared.controller->clone();
  library->reset(flight.initial_state(), 0.0);
  std::vector<Eigen::VectorXd> inputs;
  std::vector<std::vector<double>> carried;  // after each sample, when the step carries a state
  const std::vector<double> carried_at_reset =
      design.carried_state ? design.carried_state(*library) : std::vector<double>{};
  for (std::size_t i = 0; i < samples.size(); ++i) {
    inputs.emplace_back(design.initial_input.size());
    try {
      library->control(samples.time[i], samples.measured[i], samples.reference[i], inputs.back());
    } catch (const Error&) {
      // The controller failed where the flight ended: the check holds the samples before.
      inputs.pop_back();
      break;
    }
    if (design.carried_state) carried.push_back(design.carried_state(*library));
  }
  if (inputs.empty()) throw Error("export: " + exported.label + " failed at the flight's first sample");
  samples.time.resize(inputs.size());

  const std::vector<std::size_t> starts = segment_starts(samples.size(), options);
  const auto per = std::min(samples.size(), static_cast<std::size_t>(options.samples_per_segment));
  std::vector<std::vector<double>> applied, carried_before, measured, reference, input;
  std::vector<double> time;
  std::string start_list;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    start_list += std::to_string(k * per) + ", ";
    applied.push_back(entries(starts[k] == 0 ? design.initial_input : inputs[starts[k] - 1]));
    if (design.carried_state) carried_before.push_back(starts[k] == 0 ? carried_at_reset : carried[starts[k] - 1]);
    for (std::size_t i = starts[k]; i < starts[k] + per; ++i) {
      time.push_back(samples.time[i]);
      measured.push_back(entries(samples.measured[i]));
      reference.push_back(reference_row(samples.reference[i]));
      input.push_back(entries(inputs[i]));
    }
  }
  exported.check_samples = static_cast<int>(time.size());
  std::string s = "// " + exported.check_data_file + ": " + std::to_string(time.size()) + " controller samples of " +
                  flight.scenario().name + " in " + std::to_string(starts.size()) + " runs of " + std::to_string(per) +
                  " (seed " + std::to_string(flight.settings().seed) + ", " + flight.disturbances() +
                  "), fed in order to the library's " + exported.label + " from its reset;\n"
                  "// the u it computed on each. Written by " + version_line() + ".\n#pragma once\n\nnamespace " +
                  exported.name_space + "_check {\n\n";
  s += "inline constexpr int kSegments = " + std::to_string(starts.size()) + ";\n";
  s += "inline constexpr int kSamples = " + std::to_string(time.size()) + ";\n";
  s += "inline constexpr int kSegmentStart[" + std::to_string(starts.size() + 1) + "] = {" + start_list +
       std::to_string(time.size()) + "};\n";
  s += "// The input the controller applied before each run's first sample.\n" + rows_of("kAppliedBefore", applied);
  // Called after reset() and set_applied_input() at the start of each run.
  if (design.carried_state) {
    s += "// What the step carried into each run beyond the applied input: the library's, after the sample\n"
         "// before it.\n" + rows_of("kCarriedBefore", carried_before);
    s += "template <class T>\nvoid resume_carried(" + exported.name_space + "::State<T>& state, int segment) {\n  " +
         exported.name_space + "::" + design.carried_state_setter + "(state, kCarriedBefore[segment]);\n}\n";
  } else {
    s += "// The step carries nothing beyond the applied input.\ntemplate <class T>\nvoid resume_carried(" +
         exported.name_space + "::State<T>&, int) {}\n";
  }
  s += "inline constexpr double kTime[" + std::to_string(time.size()) + "] = {" + literal_list(time, "", "", 6) + "\n};\n";
  s += rows_of("kMeasured", measured);
  s += "// Position, its integral, velocity, acceleration (NED).\n" + rows_of("kReference", reference);
  s += rows_of("kInput", input);
  return s + "\n}  // namespace " + exported.name_space + "_check\n";
}

}  // namespace

std::string identifier_of(const std::string& label) {
  std::string name;
  for (const char c : label) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name.front()))) name = "c_" + name;
  return name;
}

ExportedController export_controller(const Flight& flight, PreparedController& prepared,
                                     const ExportCheckOptions& check) {
  if (check.segments < 1 || check.samples_per_segment < 1)
    throw Error("export: the check needs at least one segment of at least one sample");
  ExportedController exported;
  exported.label = prepared.spec.label;
  exported.controller = prepared.spec.controller;
  exported.name_space = identifier_of(exported.label);
  exported.header_file = exported.label + ".hpp";
  exported.check_data_file = exported.label + "_check_data.hpp";
  exported.driver_file = exported.label + "_check.cpp";
  const std::unique_ptr<Controller> designed = prepared.controller->clone();
  designed->reset(flight.initial_state(), 0.0);
  const ExportedDesign design = design_of(*designed, prepared.settings, exported.label);
  exported.checksum_double = design.data.checksum_double();
  exported.checksum_float = design.data.checksum_float();
  exported.header = header_of(flight, prepared, exported, design);
  exported.check_data = check_data_of(flight, prepared, design, check, exported);
  exported.driver = "// " + exported.driver_file + ": the check of " + exported.header_file + " (written by " +
                    version_line() + ").\n#include \"" + exported.header_file + "\"\n#include \"" +
                    exported.check_data_file + "\"\n\nnamespace exported = " + exported.name_space +
                    ";\nnamespace check = " + exported.name_space + "_check;\n\n" +
                    std::string(onboard_source("check_driver.cpp"));
  return exported;
}

}  // namespace thetad
