#pragma once

#include <nlohmann/json.hpp>

#include "core/log_column.hpp"

namespace thetad {

// Run results of an earlier format_version under the current names (docs/glossary.md), so that
// every reader (replay, read_run_files and through it `thetad plot` and thetad.plot) knows one set
// of names, and the old ones are written down here alone (experiment/result_json.hpp lists what
// each version changed).

// `result` with the names of kRunFormatVersion: the metrics flattened and renamed, the settings and
// the log's columns renamed, the values unchanged but for the in-flight step times (ns → µs). What
// an earlier version did not record stays absent (rms_error_m and max_axis_error_m before version 4,
// and the fields later versions added). "format_version" still says what the file was. A result of
// the current version comes back as it is.
nlohmann::ordered_json with_current_names(nlohmann::ordered_json result);

// The log's wall-clock column as versions 1 to 3 named it (sim::step_time_column() names it now).
inline LogColumn earlier_step_time_column() { return {"compute", "ns"}; }
// `column` under its current name.
LogColumn current_log_column(LogColumn column);

}  // namespace thetad
