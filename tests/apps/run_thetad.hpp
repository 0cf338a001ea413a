#pragma once

// Runs the built thetad program (THETAD_BINARY, set in tests/CMakeLists.txt) as a user does, for
// the tests of the command line.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace thetad::testing {

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

struct Output {
  int status = -1;
  std::string out;
  std::string err;
};

// `environment` (VAR=value ...) and thetad with `arguments` (a shell command-line tail), CI set so
// that progress comes as plain lines, in the working folder `cwd` (default: the current one), run
// through `launcher` (a command prefix, e.g. one setting a resource limit) when given; stdout and
// stderr are captured through files in `directory`.
inline Output run_thetad(const std::filesystem::path& directory, const std::string& arguments,
                         const std::string& environment = "", const std::filesystem::path& cwd = {},
                         const std::string& launcher = "") {
  const std::string change = cwd.empty() ? std::string() : "cd '" + cwd.string() + "' && ";
  const std::string command = change + "CI=1 " + environment + " " + launcher + std::string(THETAD_BINARY) + " " + arguments +
                              " >" + (directory / "stdout.txt").string() + " 2>" + (directory / "stderr.txt").string();
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_text(directory / "stdout.txt"),
          read_text(directory / "stderr.txt")};
}

}  // namespace thetad::testing
