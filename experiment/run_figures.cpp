#include "experiment/run_figures.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sim/simulator.hpp"
#include "core/text_file.hpp"
#include "experiment/python_script.hpp"
#include "experiment/run_files.hpp"

namespace thetad {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// `directory` absolute and normalized, without a trailing separator ("out/" names "out").
fs::path directory_path(const fs::path& directory) {
  const fs::path path = fs::absolute(directory).lexically_normal();
  return path.has_filename() ? path : path.parent_path();
}

// The runs of a folder, each checked against its result file (read_result_folder); every run must
// have a log to draw, and `baseline`, if given, must be one of them.
std::vector<StoredRun> read_inputs(const fs::path& in, const std::string& baseline) {
  if (!fs::is_directory(in)) throw Error(in.string() + ": no such directory");
  std::vector<StoredRun> runs = read_result_folder(in);
  for (const StoredRun& run : runs) {
    if (run.csv_file.empty())
      throw Error(run.json_file.string() + ": run '" + run.label + "' has no log to draw (flown --summary-only)");
  }
  if (!baseline.empty() && std::none_of(runs.begin(), runs.end(),
                                        [&](const StoredRun& run) { return run.label == baseline; })) {
    std::string message = "baseline ";
    message.append(baseline).append(": no run of ").append(in.string()).append(" has that label (runs:");
    for (const StoredRun& run : runs) message.append(" ").append(run.label);
    throw Error(message.append(")"));
  }
  return runs;
}

std::string manifest(const std::vector<StoredRun>& runs, const FigureOptions& options, const fs::path& staging) {
  ordered_json j;
  j["out"] = fs::absolute(staging).string();
  j["formats"] = options.formats;
  j["dpi"] = options.dpi;
  j["baseline"] = options.baseline;
  j["schema"] = ordered_json::array();
  // Every column of the runs, by name, once, and the schema's last column, the control step's wall
  // time, which runs flown without timing do not write.
  std::set<std::string> named;
  for (const auto& run : runs) {
    for (const auto& column : run.columns) {
      if (named.insert(column.name).second) j["schema"].push_back({{"name", column.name}, {"unit", column.unit}});
    }
  }
  const LogColumn step_time = sim::step_time_column();
  if (named.count(step_time.name) == 0) j["schema"].push_back({{"name", step_time.name}, {"unit", step_time.unit}});
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

std::string trimmed(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

}  // namespace

std::vector<fs::path> draw_run_figures(const fs::path& in, const fs::path& out_folder, const FigureOptions& options) {
  const std::vector<StoredRun> runs = read_inputs(in, options.baseline);
  const fs::path script = options.script.empty() ? shipped_script("plot_run.py") : options.script;
  if (!fs::is_regular_file(script)) throw Error("plot script " + script.string() + " not found");

  // The staging directory is out's sibling, on the same file system so that the figures can be
  // renamed into place.
  const fs::path out = directory_path(out_folder);
  std::error_code error;
  fs::create_directories(out.parent_path(), error);
  if (error) throw Error("cannot create directory " + out.parent_path().string() + ": " + error.message());
  std::string staging_name = ".";  // appended, not "." + ...: GCC 12 warns falsely (-Wrestrict) on that
  staging_name += out.filename().string() + ".plot-partial-" + std::to_string(::getpid());
  const Staging staging{out.parent_path() / staging_name};
  fs::remove_all(staging.path, error);
  if (!fs::create_directory(staging.path, error)) {
    throw Error("cannot create directory " + staging.path.string() + ": " + error.message());
  }
  // The script's own files start with a dot and stay behind in the staging directory.
  const fs::path manifest_file = staging.path / ".manifest.json";
  const fs::path log = staging.path / ".log";
  write_file_atomically(manifest_file, manifest(runs, options, staging.path));

  std::fprintf(stderr, "plot: drawing %zu run(s) from %s\n", runs.size(), in.c_str());
  const int status = run_python_script(script, {manifest_file.string()}, log);
  const std::string messages = trimmed(read_text_file(log));
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
  std::vector<fs::path> written;
  for (const auto& figure : figures) {
    fs::rename(figure, out / figure.filename());
    written.push_back(out / figure.filename());
  }
  return written;
}

}  // namespace thetad
