#include "apps/thetad/plot_command.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sim/simulator.hpp"
#include "experiment/run_files.hpp"
#include "experiment/scenario_files.hpp"

extern char** environ;

namespace thetad::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// `directory` absolute and normalized, without a trailing separator ("out/" names "out").
fs::path directory_path(const fs::path& directory) {
  const fs::path path = fs::absolute(directory).lexically_normal();
  return path.has_filename() ? path : path.parent_path();
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read " + file.string() + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The runs of a folder, each checked against its result file (read_result_folder); every run must
// have a log to draw, and `baseline`, if given, must be one of them.
std::vector<StoredRun> read_inputs(const fs::path& in, const std::string& baseline) {
  if (!fs::is_directory(in)) throw Error("--in " + in.string() + ": no such directory");
  std::vector<StoredRun> runs = read_result_folder(in);
  for (const StoredRun& run : runs) {
    if (run.csv_file.empty())
      throw Error(run.json_file.string() + ": run '" + run.label + "' has no log to draw (flown --summary-only)");
  }
  if (!baseline.empty() && std::none_of(runs.begin(), runs.end(),
                                        [&](const StoredRun& run) { return run.label == baseline; })) {
    std::string message = "--baseline ";
    message.append(baseline).append(": no run of ").append(in.string()).append(" has that label (runs:");
    for (const StoredRun& run : runs) message.append(" ").append(run.label);
    throw Error(message.append(")"));
  }
  return runs;
}

std::string manifest(const std::vector<StoredRun>& runs, const PlotArguments& arguments, const fs::path& staging) {
  ordered_json j;
  j["out"] = fs::absolute(staging).string();
  j["formats"] = arguments.formats;
  j["dpi"] = arguments.dpi;
  j["baseline"] = arguments.baseline;
  j["schema"] = ordered_json::array();
  for (const auto& column : sim::log_schema()) j["schema"].push_back({{"name", column.name}, {"unit", column.unit}});
  j["runs"] = ordered_json::array();
  for (const auto& run : runs) {
    ordered_json columns = ordered_json::array();
    for (const auto& column : run.columns) columns.push_back(column.name);
    j["runs"].push_back({{"name", run.label},
                         {"csv", fs::absolute(run.csv_file).string()},
                         {"columns", columns},
                         {"summary", run.result}});
  }
  return j.dump(1) + "\n";
}

// Removes the staging directory however run_plot leaves.
struct Staging {
  fs::path path;
  ~Staging() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

// Runs `python script manifest` with MPLBACKEND=Agg, stdout and stderr to `log`; the exit status.
int run_script(const std::string& python, const fs::path& script, const fs::path& manifest_file, const fs::path& log) {
  std::vector<std::string> environment{"MPLBACKEND=Agg"};
  for (char** entry = environ; *entry != nullptr; ++entry) {
    if (std::strncmp(*entry, "MPLBACKEND=", 11) != 0) environment.emplace_back(*entry);
  }
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
  std::vector<std::string> argument_text{python, script.string(), manifest_file.string()};
  std::vector<char*> argv;
  for (auto& argument : argument_text) argv.push_back(argument.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, python.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    throw Error("cannot run the plot interpreter '" + python + "': " + std::strerror(spawn_error) +
                " (Debian's python3-matplotlib is needed: make deps; or set THETAD_PYTHON)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error(std::string("waiting for the plot script: ") + std::strerror(errno));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string trimmed(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

// The first plotting script of the data folders: the installed one for an installed thetad (it
// must not depend on the source tree it was built from), the source tree's for a build.
fs::path default_plot_script() {
  std::error_code error;
  for (const fs::path& folder : data_directories()) {
    if (fs::is_regular_file(folder / "scripts" / "plot_run.py", error)) return folder / "scripts" / "plot_run.py";
  }
  return data_directories().back() / "scripts" / "plot_run.py";
}

}  // namespace

CLI::App* add_plot_command(CLI::App& app, PlotArguments& arguments) {
  auto* plot = app.add_subcommand(
      "plot", "Draw the paper's figures (Figs. 2-17) and comparison figures for the runs in a directory");
  plot->add_option("--in", arguments.in, "Directory written by thetad compare (or thetad run)")->required();
  plot->add_option("--out", arguments.out, "Directory for the figures (created; existing files are replaced)")
      ->required();
  plot->add_option("--format,--formats", arguments.formats, "Comma-separated file formats (png, svg, pdf)")
      ->delimiter(',')
      ->check(CLI::IsMember({"png", "svg", "pdf"}))
      ->capture_default_str();
  plot->add_option("--dpi", arguments.dpi, "Resolution of raster formats (the figures are 8.5 or 17.6 cm wide)")
      ->check(CLI::Range(30, 600))
      ->capture_default_str();
  plot->add_option("--baseline", arguments.baseline,
                   "Label of the run the difference panels (Euler angles) compare with; default: the first run");
  arguments.script = default_plot_script();
  plot->add_option("--script", arguments.script, "The plotting script")->capture_default_str();
  return plot;
}

int run_plot(const PlotArguments& arguments) {
  const std::vector<StoredRun> runs = read_inputs(arguments.in, arguments.baseline);
  const fs::path& script = arguments.script;
  if (!fs::is_regular_file(script)) throw Error("plot script " + script.string() + " not found (see --script)");
  const char* python_variable = std::getenv("THETAD_PYTHON");
  // Debian's interpreter: the one that sees python3-matplotlib, whatever python3 is first on PATH.
  const std::string python = python_variable != nullptr ? python_variable : "/usr/bin/python3";

  // The staging directory is out's sibling, on the same file system so that the figures can be
  // renamed into place.
  const fs::path out = directory_path(arguments.out);
  std::error_code error;
  fs::create_directories(out.parent_path(), error);
  if (error) throw Error("cannot create directory " + out.parent_path().string() + ": " + error.message());
  const Staging staging{out.parent_path() / ("." + out.filename().string() + ".plot-partial-" + std::to_string(::getpid()))};
  fs::remove_all(staging.path, error);
  if (!fs::create_directory(staging.path, error)) {
    throw Error("cannot create directory " + staging.path.string() + ": " + error.message());
  }
  // The script's own files start with a dot and stay behind in the staging directory.
  const fs::path manifest_file = staging.path / ".manifest.json";
  const fs::path log = staging.path / ".log";
  write_file_atomically(manifest_file, manifest(runs, arguments, staging.path));

  std::fprintf(stderr, "plot: drawing %zu run(s) from %s\n", runs.size(), arguments.in.c_str());
  const int status = run_script(python, script, manifest_file, log);
  const std::string messages = trimmed(read_text(log));
  if (status != 0) {
    throw Error(script.filename().string() + " failed (exit status " + std::to_string(status) + ")" +
                (messages.empty() ? std::string() : ": " + messages));
  }
  if (!messages.empty()) std::fprintf(stderr, "%s\n", messages.c_str());

  std::vector<fs::path> figures;
  for (const auto& entry : fs::directory_iterator(staging.path)) {
    if (entry.path().filename().string().front() != '.') figures.push_back(entry.path());
  }
  if (figures.empty()) throw Error(script.filename().string() + " drew no figures");
  std::sort(figures.begin(), figures.end());
  fs::create_directories(out, error);
  if (error) throw Error("cannot create directory " + out.string() + ": " + error.message());
  for (const auto& figure : figures) fs::rename(figure, out / figure.filename());

  std::printf("Wrote %zu files to %s:\n", figures.size(), arguments.out.c_str());
  for (const auto& figure : figures) std::printf("  %s\n", (arguments.out / figure.filename()).c_str());
  return 0;
}

}  // namespace thetad::app
