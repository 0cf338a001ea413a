#include "experiment/controller_build.hpp"

#include "core/error.hpp"
#include "settings/settings.hpp"

namespace thetad {

namespace {

// Runs `read` with settings errors located in the spec's file.
template <class Read>
decltype(auto) in_source(const ControllerSpec& spec, Read&& read) {
  return spec.settings_source.empty() ? read() : with_settings_source(spec.settings_source, std::forward<Read>(read));
}

// "controller 'tuned' (theta-d, settings best.yaml:3:3)".
std::string describe(const ControllerSpec& spec) {
  std::string text = "controller '";
  text.append(spec.label).append("' (").append(spec.controller);
  if (spec.settings_source.empty()) return text.append(", default settings)");
  text.append(", settings ").append(spec.settings_source);
  if (const YAML::Mark mark = spec.settings.Mark(); !mark.is_null())
    text.append(":").append(std::to_string(mark.line + 1)).append(":").append(std::to_string(mark.column + 1));
  return text.append(")");
}

}  // namespace

BuiltController build_controller(const ControllerSpec& spec, const ControllerContext& context) {
  const ControllerRegistry& registry = ControllerRegistry::instance();
  if (spec.settings_file.IsMap()) {
    for (const auto& block : spec.settings_file) {
      const std::string name = block.first.Scalar();
      if (name == spec.controller) continue;
      try {
        in_source(spec, [&] { registry.check(name, block.second, context); });
      } catch (const SettingsError&) {
        throw;
      } catch (const Error& error) {
        std::string message = spec.settings_source;
        message.append(": the block for '").append(name).append("' cannot be used here: ").append(error.what());
        throw Error(message);
      }
    }
  }
  try {
    BuiltController built = in_source(spec, [&] { return registry.build(spec.controller, spec.settings, context); });
    // A controller may design at reset() (θ–D solves its CARE at the initial state): once here
    // too, so that such a failure also names its source before anything flies.
    built.controller->reset(context.initial_state, context.initial_time);
    return built;
  } catch (const SettingsError&) {
    throw;
  } catch (const Error& error) {
    throw Error(describe(spec).append(": cannot be designed with these settings: ").append(error.what()));
  }
}

}  // namespace thetad
