#include "experiment/python_script.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "core/error.hpp"
#include "experiment/scenario_files.hpp"

extern char** environ;

namespace thetad {

namespace fs = std::filesystem;

std::string python_interpreter() {
  const char* python = std::getenv("THETAD_PYTHON");
  return python != nullptr ? python : "/usr/bin/python3";
}

fs::path shipped_script(const std::string& name) {
  std::error_code error;
  for (const fs::path& folder : data_directories()) {
    if (fs::is_regular_file(folder / "scripts" / name, error)) return folder / "scripts" / name;
  }
  return data_directories().back() / "scripts" / name;
}

int run_python_script(const fs::path& script, const std::vector<std::string>& arguments, const fs::path& log) {
  const std::string python = python_interpreter();
  std::vector<std::string> environment{"MPLBACKEND=Agg"};
  for (char** entry = environ; *entry != nullptr; ++entry) {
    if (std::strncmp(*entry, "MPLBACKEND=", 11) != 0) environment.emplace_back(*entry);
  }
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
  std::vector<std::string> argument_text{python, script.string()};
  argument_text.insert(argument_text.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& argument : argument_text) argv.push_back(argument.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, python.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    throw Error("cannot run the Python interpreter '" + python + "' for " + script.filename().string() + ": " +
                std::strerror(spawn_error) + " (Debian's python3-matplotlib is needed: make deps; or set THETAD_PYTHON)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("waiting for " + script.filename().string() + ": " + std::strerror(errno));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace thetad
