#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/sim/simulator.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_result.hpp"
#include "experiment/sha256.hpp"

namespace thetad {

// Creates `folder` if needed and checks that a file can be written in it, so that a typo or a
// read-only folder is found before a flight, not after. Throws thetad::Error naming the folder.
void prepare_output_folder(const std::filesystem::path& folder);

// A CSV streamed into `out` row by row, in 1 MiB chunks, with the SHA-256 of what was written:
// shortest round-trip numbers, exact and the same bytes for the same doubles on every run.
class CsvStream {
 public:
  CsvStream(std::ostream& out, const std::string& header);
  void row(const double* values, std::size_t count);
  // Flushes and returns the file's digest and row count (the file name is the caller's).
  LogFile finish();

 private:
  void flush();
  std::ostream& out_;
  Sha256 digest_;
  std::string chunk_;
  long long rows_ = 0;
};

struct RunFiles {
  std::filesystem::path csv;  // empty for a summary-only run
  std::filesystem::path json;
};

// Writes (creating `folder` if needed) <folder>/<label>.csv (the log; not for a summary-only run) and <folder>/<label>.json (the
// result, kRunFormat). Both are written under temporary names, then renamed CSV first and JSON
// last: the JSON names its CSV with the CSV's SHA-256, so a reader can tell a pair that does not
// belong together (a kill between the renames) and trusts a CSV only through its JSON. Throws
// thetad::Error naming the file; no temporary file is left behind.
RunFiles write_run_files(const RunResult& result, const std::filesystem::path& folder);

// The same commit for any result: `write_log` (none: no log) writes the CSV and returns its
// SHA-256 and row count; `result` makes the JSON, given the log it must name (null: none).
using LogWriter = std::function<LogFile(std::ostream&)>;
RunFiles write_result_files(const std::filesystem::path& folder, const std::string& label, const LogWriter& write_log,
                            const std::function<nlohmann::ordered_json(const LogFile*)>& result);

// A result read back: the JSON, and its CSV checked against it.
struct StoredRun {
  std::string label;
  std::filesystem::path json_file;
  std::filesystem::path csv_file;  // empty for a summary-only run
  nlohmann::ordered_json result;  // under the current names (with_current_names)
  std::vector<LogColumn> columns;  // of the CSV, under their current names
};

// Reads <label>.json and checks its format and, when it names a log, that the CSV exists, has that
// SHA-256 and the header the JSON records (the helicopter's log_columns() in results written before
// the JSON recorded it). A result of an earlier format_version comes with the current names.
// Throws thetad::Error naming the file and the reason.
StoredRun read_run_files(const std::filesystem::path& json_file);

// Every run in `folder`: through its comparison.json (its order; each result must be the file it
// recorded) when there is one, else every <label>.json of format kRunFormat in name order, which
// must all have flown one scenario file with one seed. Throws thetad::Error when there is none.
std::vector<StoredRun> read_result_folder(const std::filesystem::path& folder);

}  // namespace thetad
