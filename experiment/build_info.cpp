#include "experiment/build_info.hpp"

#include <Eigen/Core>

#include "experiment/build_config.hpp"

namespace thetad {

const char* git_revision();  // generated at build time (cmake/git_revision.cmake)

const BuildInfo& build_info() {
  static const BuildInfo info{
      THETAD_VERSION,
      git_revision(),
      THETAD_BUILD_TYPE,
      THETAD_COMPILER,
      THETAD_CXX_FLAGS,
      std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
          std::to_string(EIGEN_MINOR_VERSION) + " (" + Eigen::SimdInstructionSetsInUse() + ")",
      THETAD_LAPACK,
  };
  return info;
}

std::string version_line() {
  const BuildInfo& info = build_info();
  std::string line = "thetad " + info.version + " (";
  if (!info.git_revision.empty()) line += "git " + info.git_revision + ", ";
  return line + info.build_type + ", " + info.compiler + ")";
}

}  // namespace thetad
