#include "experiment/controller_spec.hpp"

#include <algorithm>
#include <cctype>

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "core/text_file.hpp"
#include "settings/settings.hpp"
#include "settings/yaml_document.hpp"

namespace thetad {

namespace {

std::string lower_case(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// The block for `name` in a settings file; a null node when there is none.
YAML::Node block_of(const YAML::Node& file, const std::string& name) {
  return file.IsMap() && file[name] ? file[name] : YAML::Node();
}

}  // namespace

YAML::Node load_settings_file(const std::filesystem::path& file) {
  const YAML::Node root = load_yaml_file(file);
  if (!root.IsDefined() || root.IsNull()) return root;
  if (!root.IsMap())
    throw SettingsError("settings", "expected a map from controller name to its settings", root.Mark(), file.string());
  for (const auto& item : root) {
    const std::string name = item.first.Scalar();
    if (!ControllerRegistry::instance().contains(name))
      throw SettingsError(name, "unknown controller (known: " + ControllerRegistry::instance().known_names() + ")", item.first.Mark(),
                          file.string());
    check_block(item.second, name, file.string());
  }
  return root;
}

void check_label(const std::string& label) {
  const auto allowed = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '+' || c == '-';
  };
  constexpr const char* kRule = "a label names files, so it must be 1-64 characters from A-Z a-z 0-9 . _ + - and "
                                "not start with '.' or '-'";
  if (label.empty()) throw Error(std::string("an empty label: ") + kRule);
  const bool valid = label.size() <= 64 && label.front() != '.' && label.front() != '-' &&
                     std::all_of(label.begin(), label.end(), allowed);
  if (!valid) throw Error("label '" + escaped_utf8(label) + "': " + kRule);
  if (lower_case(label) == "comparison")
    throw Error("label '" + label + "': the name of a compare's own file (comparison.json); choose another");
}

void check_labels(const std::vector<ControllerSpec>& specs) {
  for (auto it = specs.begin(); it != specs.end(); ++it) {
    check_label(it->label);
    // Labels name files: two that differ only in case are one file on some file systems.
    const auto same = [&](const ControllerSpec& other) { return lower_case(other.label) == lower_case(it->label); };
    if (const auto first = std::find_if(specs.begin(), it, same); first != it)
      throw Error("label '" + it->label + "' is used twice" +
                  (first->label == it->label ? std::string() : " (as '" + first->label + "': labels name files)") +
                  ": give each controller its own (LABEL=NAME)");
  }
}

ControllerSpec parse_controller_spec(const std::string& text, const YAML::Node& fallback,
                                     const std::string& fallback_source) {
  ControllerSpec spec;
  // The spec as the user typed it, for messages: command-line text may hold any bytes.
  const std::string given = "controller '" + escaped_utf8(text) + "'";
  std::string rest = text;
  const auto equals = rest.find('=');
  if (equals != std::string::npos) {
    spec.label = rest.substr(0, equals);
    rest = rest.substr(equals + 1);
  }
  std::string file;
  if (const auto colon = rest.find(':'); colon != std::string::npos) {
    file = rest.substr(colon + 1);
    rest = rest.substr(0, colon);
    if (file.empty()) throw Error(given + ": no settings file after ':'");
  }
  spec.controller = rest;
  if (!ControllerRegistry::instance().contains(spec.controller))
    throw Error(given + ": unknown controller '" + escaped_utf8(spec.controller) + "' (known: " +
                ControllerRegistry::instance().known_names() + ")");
  if (equals == std::string::npos) {
    spec.label = spec.controller;
  } else if (spec.label.empty()) {
    throw Error(given + ": an empty label before '=' (write LABEL=" + spec.controller + ", or " + spec.controller +
                " alone to be labelled by the controller's name)");
  }
  try {
    check_label(spec.label);
  } catch (const Error& error) {
    throw Error(given + ": " + error.what());
  }
  if (!file.empty()) {
    const YAML::Node settings = load_settings_file(file);
    if (block_of(settings, spec.controller).IsNull())
      throw Error(given + ": " + escaped_utf8(file) + " has no block for '" + spec.controller + "'");
    spec.settings = block_of(settings, spec.controller);
    spec.settings_source = file;
    spec.settings_file = settings;
  } else if (fallback.IsDefined() && !fallback.IsNull()) {
    spec.settings = block_of(fallback, spec.controller);
    spec.settings_source = fallback_source;
    spec.settings_file = fallback;
  }
  return spec;
}

std::vector<ControllerSpec> parse_controller_specs(const std::vector<std::string>& texts,
                                                   const std::filesystem::path& settings_file) {
  const YAML::Node settings = settings_file.empty() ? YAML::Node() : load_settings_file(settings_file);
  std::vector<ControllerSpec> specs;
  for (const auto& text : texts) {
    if (text == kAllControllers) {
      for (const auto& name : compared_controllers())
        specs.push_back(parse_controller_spec(name, settings, settings_file.string()));
    } else {
      specs.push_back(parse_controller_spec(text, settings, settings_file.string()));
    }
  }
  check_labels(specs);
  return specs;
}

std::vector<std::string> compared_controllers() {
  std::vector<std::string> names;
  for (const auto& name : ControllerRegistry::instance().names())
    if (!name.starts_with("example-")) names.push_back(name);
  return names;
}

std::vector<ControllerSpec> load_controller_specs(const std::filesystem::path& file) {
  const YAML::Node root = load_yaml_file(file);
  return with_settings_source(file.string(), [&] {
    const Settings top(root);
    top.allow_only({"controllers"});
    if (!top.has("controllers")) throw top.error("controllers", "missing (required)");
    return read_controller_specs(root["controllers"], file.string());
  });
}

std::vector<ControllerSpec> read_controller_specs(const YAML::Node& list, const std::string& source) {
  return with_settings_source(source, [&] {
    if (!list.IsSequence() || list.size() == 0)
      throw SettingsError("controllers", "expected a non-empty list of {label, controller, settings}", list.Mark());
    std::vector<ControllerSpec> specs;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = "controllers[" + std::to_string(i) + "]";
      const Settings item(list[i], path);
      item.allow_only({"label", "controller", "settings"});
      if (!item.has("controller")) throw item.error("controller", "missing (required)");
      ControllerSpec spec;
      spec.controller = item.string("controller", "");
      if (!ControllerRegistry::instance().contains(spec.controller))
        throw item.error("controller", "unknown controller '" + spec.controller + "' (known: " + ControllerRegistry::instance().known_names() + ")");
      spec.label = item.string("label", spec.controller);
      try {
        check_label(spec.label);
      } catch (const Error& error) {
        throw item.error("label", error.what());
      }
      const YAML::Node settings = list[i]["settings"];
      if (settings && settings.IsScalar()) {
        const std::filesystem::path file = std::filesystem::path(source).parent_path() / settings.Scalar();
        const YAML::Node blocks = load_settings_file(file);
        if (block_of(blocks, spec.controller).IsNull())
          throw item.error("settings", file.string() + " has no block for '" + spec.controller + "'");
        spec.settings = block_of(blocks, spec.controller);
        spec.settings_source = file.string();
        spec.settings_file = blocks;
      } else if (settings && !settings.IsNull()) {
        if (!settings.IsMap()) throw item.error("settings", "expected a settings map or the name of a settings file");
        spec.settings = settings;
        spec.settings_source = source;
      }
      specs.push_back(std::move(spec));
    }
    check_labels(specs);
    return specs;
  });
}

}  // namespace thetad
