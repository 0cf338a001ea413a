#include "experiment/json_file.hpp"

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

nlohmann::ordered_json read_json_file(const std::filesystem::path& file) {
  try {
    return nlohmann::ordered_json::parse(read_text_file(file));
  } catch (const nlohmann::ordered_json::parse_error& error) {
    throw Error(file.string() + ": not valid JSON: " + error.what());
  }
}

}  // namespace thetad
