#include "experiment/run_files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "experiment/result_json.hpp"
#include "experiment/result_names.hpp"
#include "experiment/sha256.hpp"
#include "experiment/json_file.hpp"

namespace thetad {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::string header_line(const std::vector<LogColumn>& columns) {
  std::string header;
  for (const auto& column : columns) {
    if (!header.empty()) header += ',';
    header += column.header();
  }
  return header;
}

// Writes the log as CSV into `out` (the wall-clock column only with timing).
LogFile write_csv(const sim::RunLog& log, bool timing, std::ostream& out) {
  const std::vector<LogColumn> columns = log_columns(log.columns, timing);
  CsvStream csv(out, header_line(columns));
  const std::size_t schema = log.columns.size(), written = columns.size();
  for (std::size_t i = 0; i < log.values.size(); i += schema) csv.row(log.values.data() + i, written);
  return csv.finish();
}

// The CSV's header must name `columns` in order; the error names the first difference, so that a
// log of another thetad version is recognized as such.
void check_header(const fs::path& csv, const std::vector<LogColumn>& columns) {
  std::ifstream in(csv, std::ios::binary);
  std::string line;
  std::getline(in, line);
  if (line == header_line(columns)) return;
  std::vector<std::string> found;
  std::istringstream fields(line);
  for (std::string field; std::getline(fields, field, ',');) found.push_back(field);
  const std::string where = csv.string() + ": header does not match thetad's run-log schema: ";
  for (std::size_t i = 0; i < std::max(found.size(), columns.size()); ++i) {
    const std::string column = std::to_string(i + 1);
    if (i >= found.size()) throw Error(where + "column " + column + " '" + columns[i].header() + "' is missing");
    if (i >= columns.size()) throw Error(where + "unexpected column " + column + " '" + found[i] + "'");
    if (found[i] != columns[i].header())
      throw Error(where + "column " + column + " is '" + found[i] + "', expected '" + columns[i].header() + "'");
  }
}

class FolderLock {
 public:
  explicit FolderLock(const fs::path& folder) : descriptor_(open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (descriptor_ >= 0 && flock(descriptor_, LOCK_EX) == 0) return;
    const std::string reason = std::strerror(errno);
    if (descriptor_ >= 0) close(descriptor_);
    throw Error("cannot lock " + folder.string() + " to write a result: " + reason);
  }
  ~FolderLock() {
    if (descriptor_ >= 0) close(descriptor_);  // releases the lock
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int descriptor_;
};

}  // namespace

CsvStream::CsvStream(std::ostream& out, const std::string& header) : out_(out), chunk_(header + "\n") {}

void CsvStream::row(const double* values, std::size_t count) {
  char number[32];
  for (std::size_t c = 0; c < count; ++c) {
    const auto [end, status] = std::to_chars(number, number + sizeof number, values[c]);
    chunk_.append(number, end);
    chunk_.push_back(c + 1 == count ? '\n' : ',');
  }
  ++rows_;
  if (chunk_.size() > (1u << 20)) flush();
}

void CsvStream::flush() {
  digest_.update(chunk_);
  out_.write(chunk_.data(), static_cast<std::streamsize>(chunk_.size()));
  chunk_.clear();
}

LogFile CsvStream::finish() {
  flush();
  return {{}, digest_.hex(), rows_};
}

void prepare_output_folder(const fs::path& folder) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw Error("--out " + folder.string() + ": cannot create the folder: " + error.message());
  if (!fs::is_directory(folder)) throw Error("--out " + folder.string() + ": not a folder");
  const PartialFile probe(folder / "write-test");
  std::ofstream out(probe.path(), std::ios::binary);
  if (!out) throw Error("--out " + folder.string() + ": cannot write there: " + std::strerror(errno));
}

RunFiles write_result_files(const fs::path& folder, const std::string& label, const LogWriter& write_log,
                            const std::function<Json(const LogFile*)>& result) {
  RunFiles files{{}, folder / (label + ".json")};
  std::error_code created;
  fs::create_directories(folder, created);
  if (created) throw Error("cannot create " + folder.string() + ": " + created.message());
  std::optional<PartialFile> csv;
  LogFile log;
  if (write_log) {
    files.csv = folder / (label + ".csv");
    csv.emplace(files.csv);
    csv->write([&](std::ostream& out) { log = write_log(out); });
    log.file = files.csv.filename().string();
  }
  PartialFile json(files.json);
  json.write([&](std::ostream& out) { out << result(csv ? &log : nullptr).dump(2) << '\n'; });
  // One commit per folder at a time: two thetad processes writing one label into one folder leave
  // the pair of one of them, never the log of one beside the result of the other.
  const FolderLock lock(folder);
  if (csv) csv->commit();
  try {
    json.commit();
  } catch (const Error&) {
    // A log whose result could not be committed must not stand alone under the final name.
    std::error_code ignored;
    fs::remove(files.csv, ignored);
    throw;
  }
  if (!csv) {
    // A log left by an earlier run under this label would sit beside a result that does not name it.
    std::error_code ignored;
    fs::remove(folder / (label + ".csv"), ignored);
  }
  return files;
}

RunFiles write_run_files(const RunResult& result, const fs::path& folder) {
  const bool timing = result.summary.settings.measure_compute_time;
  LogWriter write_log;
  if (result.summary.settings.keep_log)
    write_log = [&](std::ostream& out) { return write_csv(result.log, timing, out); };
  return write_result_files(folder, result.spec.label, write_log,
                            [&](const LogFile* log) { return result_json(result, log); });
}

StoredRun read_run_files(const fs::path& json_file) {
  StoredRun run;
  run.json_file = json_file;
  const Json file = read_json_file(json_file);
  const std::string where = json_file.string() + ": ";
  if (!file.is_object() || file.value("format", "") != kRunFormat)
    throw Error(where + "not a thetad run result (format '" + std::string(kRunFormat) +
                "'; results of an older thetad must be flown again)");
  run_format_version(file, json_file.string());
  run.result = with_current_names(file);
  run.label = run.result.value("label", "");
  const Json log = file.value("log", Json(nullptr));
  if (log.is_null()) return run;
  const std::string csv_name = log.value("csv", "");
  run.csv_file = json_file.parent_path() / csv_name;
  if (csv_name.empty() || !fs::exists(run.csv_file))
    throw Error(where + "its log " + run.csv_file.string() + " is missing");
  if (sha256_of_file(run.csv_file) != log.value("sha256", ""))
    throw Error(where + "its log " + run.csv_file.string() +
                " has another SHA-256 than the result records: the two files come from different runs");
  // The header is checked as the file wrote it; the columns are then given their current names.
  if (log.contains("columns")) {
    for (const auto& column : log.at("columns"))
      run.columns.push_back({column.at("name").get<std::string>(), column.at("unit").get<std::string>()});
  } else {
    // Version 1 recorded no columns: the helicopter's, the wall-clock one under its name then.
    run.columns = log_columns(sim::helicopter_log_schema(), run.result.at("settings").at("timing").get<bool>());
    if (!run.columns.empty() && run.columns.back().header() == sim::step_time_column().header())
      run.columns.back() = earlier_step_time_column();
  }
  check_header(run.csv_file, run.columns);
  for (LogColumn& column : run.columns) column = current_log_column(column);
  return run;
}

std::vector<StoredRun> read_result_folder(const fs::path& folder) {
  if (!fs::is_directory(folder)) throw Error(folder.string() + ": no such directory");
  std::vector<StoredRun> runs;
  const fs::path comparison = folder / "comparison.json";
  if (fs::exists(comparison)) {
    const Json j = read_json_file(comparison);
    try {
      for (const auto& run : j.at("runs")) {
        const fs::path file = folder / run.at("json").get<std::string>();
        if (fs::exists(file) && sha256_of_file(file) != run.at("json_sha256").get<std::string>())
          throw Error(comparison.string() + ": " + file.string() +
                      " has been replaced since the compare (its SHA-256 differs from the recorded one)");
        runs.push_back(read_run_files(file));
      }
    } catch (const Json::exception& error) {
      throw Error(comparison.string() + ": not a thetad comparison: " + error.what());
    }
    return runs;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".json" || entry.path().filename().string().front() == '.') continue;
    const Json j = read_json_file(entry.path());
    if (j.is_object() && j.value("format", "") == kRunFormat) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) runs.push_back(read_run_files(file));
  // Without a comparison.json the runs are drawn together only if they flew the same flight.
  const auto flight_of = [](const StoredRun& run) {
    const Json& p = run.result.at("provenance");
    return p.at("scenario").at("sha256").get<std::string>() + " seed " + std::to_string(p.at("seed").get<std::uint64_t>());
  };
  for (const StoredRun& run : runs) {
    if (flight_of(run) != flight_of(runs.front()))
      throw Error(folder.string() + ": " + run.json_file.filename().string() + " and " +
                  runs.front().json_file.filename().string() +
                  " flew different scenarios or seeds (and no comparison.json says they belong together)");
  }
  if (runs.empty())
    throw Error(folder.string() + ": no runs (expected the comparison.json of thetad compare or the result files of "
                                  "thetad run)");
  return runs;
}

}  // namespace thetad
