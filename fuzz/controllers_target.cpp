// A controllers file (`--controllers-file`): the list of {label, controller, settings}.
#include "experiment/controller_spec.hpp"
#include "fuzz/target.hpp"
#include "settings/yaml_document.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return thetad::fuzz::run(data, size, [](const std::string& text) {
    const YAML::Node root = thetad::parse_yaml(text, "fuzz-controllers.yaml");
    if (root.IsMap() && root["controllers"]) thetad::read_controller_specs(root["controllers"], "fuzz-controllers.yaml");
  });
}
