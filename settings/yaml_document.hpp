#pragma once

#include <filesystem>
#include <string>

#include <yaml-cpp/yaml.h>

namespace thetad {

// Every YAML file thetad reads (scenarios, settings, controller lists, campaigns) is parsed here,
// with the rules yaml-cpp does not enforce by itself:
//  - the text must be valid UTF-8;
//  - a key given twice in one map is an error naming both lines (yaml-cpp keeps the first silently);
//  - aliases may not expand the document beyond kMaxYamlNodes nodes (a "billion laughs" file).
// Errors are thetad::Error, "<source>:<line>:<column>: <reason>" with 1-based positions.
inline constexpr long kMaxYamlNodes = 1'000'000;

YAML::Node parse_yaml(const std::string& text, const std::string& source);

// read_text_file() (a regular file under the size cap) and parse_yaml().
YAML::Node load_yaml_file(const std::filesystem::path& file);

}  // namespace thetad
