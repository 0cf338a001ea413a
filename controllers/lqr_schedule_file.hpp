#pragma once

// The lqr-scheduled table as a JSON file (docs/lqr-scheduled.md): built once by `thetad
// design-lqr`, loaded by the controller (`table: FILE`). The file records the model it was designed
// on, so that a table designed on another model (options or parameters) is rejected.

#include <filesystem>
#include <string>

#include "controllers/lqr_schedule_design.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad {

// Errors name the file, the field and the reason.
void save_lqr_schedule(const LqrScheduleTable& table, const std::filesystem::path& file);
LqrScheduleTable load_lqr_schedule(const std::filesystem::path& file);
// Throws thetad::Error when `table` was designed on another model than `model` (`source` names it).
void check_lqr_schedule_model(const LqrScheduleTable& table, const heli::Helicopter& model, const std::string& source);

}  // namespace thetad
