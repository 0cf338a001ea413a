#include "core/sim/run_summary.hpp"

#include <cstdio>

namespace thetad::sim {

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::diverged: return "diverged";
    case RunStatus::failed: return "failed";
  }
  return "unknown";
}

std::string failure_reason(const char* source, const std::exception& error, double t) {
  char buffer[80];
  std::snprintf(buffer, sizeof buffer, "%s failed at t = %.4f s: ", source, t);
  return buffer + std::string(error.what());
}

}  // namespace thetad::sim
