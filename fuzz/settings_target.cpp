// The settings reader: a settings file (a map from controller name to its block) read by every
// built-in controller's factory, as `thetad run --settings` checks it before flying.
#include "controllers/registry.hpp"
#include "core/helicopter/helicopter.hpp"
#include "fuzz/target.hpp"
#include "settings/yaml_document.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const thetad::heli::Helicopter helicopter;
  static const thetad::ControllerContext context(helicopter, [] {
    Eigen::VectorXd x0 = Eigen::VectorXd::Zero(thetad::heli::kStateDim);
    x0(thetad::heli::kS) = 1.0;
    return x0;
  }());
  return thetad::fuzz::run(data, size, [](const std::string& text) {
    const YAML::Node root = thetad::parse_yaml(text, "fuzz-settings.yaml");
    if (!root.IsMap()) return;
    const thetad::ControllerRegistry& registry = thetad::ControllerRegistry::instance();
    for (const auto& block : root) {
      if (!block.first.IsScalar() || !registry.contains(block.first.Scalar())) continue;
      registry.check(block.first.Scalar(), block.second, context);
    }
  });
}
