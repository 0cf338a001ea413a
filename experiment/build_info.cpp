#include "experiment/build_info.hpp"

#include <dlfcn.h>

#include <filesystem>

#include <Eigen/Core>

#include "experiment/build_config.hpp"

namespace thetad {

const char* git_revision();  // generated at build time (cmake/git_revision.cmake)

namespace {

// The shared library that provides `symbol` in this process, with symbolic links resolved: Debian
// picks BLAS and LAPACK through alternatives (reference, OpenBLAS, ...), so what the build linked
// against says less than what is loaded.
std::string library_providing(const char* symbol) {
  void* address = dlsym(RTLD_DEFAULT, symbol);
  Dl_info info{};
  if (address == nullptr || dladdr(address, &info) == 0 || info.dli_fname == nullptr) return "not loaded";
  std::error_code error;
  const std::filesystem::path file = std::filesystem::canonical(info.dli_fname, error);
  return error ? info.dli_fname : file.string();
}

}  // namespace

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
      library_providing("dgemm_"),
      library_providing("dgees_"),
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
