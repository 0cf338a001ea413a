#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace thetad {

// One controller of a run or a comparison: which registered controller, with which settings, under
// which label. The label names it everywhere a result shows it (tables, file names, figures), so
// one controller can be flown twice with different settings (`paper=theta-d,tuned=theta-d:best.yaml`).
struct ControllerSpec {
  std::string label;
  std::string controller;   // a registered name (thetad list)
  YAML::Node settings;      // its settings block; a null node: every default
  std::string settings_source;  // the file the block came from, for messages and provenance; "" when none
  // The whole settings file the block came from (null when none, or an inline block): its other
  // blocks are checked too when the controller is built (build_controller).
  YAML::Node settings_file{};
};

// A settings file: a map from controller name to that controller's settings block (what `thetad
// tune` writes). Every key must be a registered controller. Errors name the file, line and field.
YAML::Node load_settings_file(const std::filesystem::path& file);

// NAME, LABEL=NAME, NAME:FILE or LABEL=NAME:FILE; FILE is a settings file whose block for NAME is
// used. Without FILE the block for NAME in `fallback` (the --settings file, or null) is used.
ControllerSpec parse_controller_spec(const std::string& text, const YAML::Node& fallback = {},
                                     const std::string& fallback_source = {});

// The specs `texts` (parse_controller_spec), those without a file of their own taking their block
// from `settings_file` (empty: none); labels checked (check_labels). The text "all" stands for
// compared_controllers(), in their order.
inline constexpr const char* kAllControllers = "all";

// Every registered controller a comparison flies (built-in or from a loaded plug-in) but the
// examples, whose names start "example-": what "all controllers" means wherever a list has a
// default (`thetad optimal`, the demo, `--controllers all`), in registration-name order.
std::vector<std::string> compared_controllers();

std::vector<ControllerSpec> parse_controller_specs(const std::vector<std::string>& texts,
                                                   const std::filesystem::path& settings_file = {});

// A file whose `controllers:` key is a list of {label, controller, settings} (read_controller_specs).
std::vector<ControllerSpec> load_controller_specs(const std::filesystem::path& file);

// A YAML list of {label, controller, settings}, settings being a settings block (a map) or the
// name of a settings file (relative to `source`'s folder); label defaults to the controller.
std::vector<ControllerSpec> read_controller_specs(const YAML::Node& list, const std::string& source);

// Throws thetad::Error unless every label is valid (see below) and no label repeats.
void check_labels(const std::vector<ControllerSpec>& specs);

// A label is 1-64 characters from [A-Za-z0-9._+-], not starting with '.' or '-': safe as a file
// name on every system and in a shell. Throws thetad::Error naming the label and the rule.
void check_label(const std::string& label);

}  // namespace thetad
