#include "experiment/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace thetad {

std::string read_text_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read " + file.string() + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("cannot read " + file.string() + ": read error");
  return text.str();
}

nlohmann::ordered_json read_json_file(const std::filesystem::path& file) {
  try {
    return nlohmann::ordered_json::parse(read_text_file(file));
  } catch (const nlohmann::ordered_json::parse_error& error) {
    throw Error(file.string() + ": not valid JSON: " + error.what());
  }
}

}  // namespace thetad
