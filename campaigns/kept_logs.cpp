#include "campaigns/kept_logs.hpp"

#include <string>

namespace thetad {

std::filesystem::path KeptLogs::run_folder(std::int64_t index) const { return out / "logs" / std::to_string(index); }

}  // namespace thetad
