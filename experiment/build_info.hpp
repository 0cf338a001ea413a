#pragma once

#include <string>

namespace thetad {

// What built this thetad: enough to tell two result files apart and to rebuild the program that
// wrote one.
struct BuildInfo {
  std::string version;       // the project version (CMake)
  std::string git_revision;  // `git describe --dirty` of the source tree at build time; "" outside a checkout
  std::string build_type;    // Release, RelWithDebInfo, ...
  std::string compiler;      // "GNU 12.2.0"
  std::string flags;         // the compiler flags of the build type, -march=native and sanitizers included
  std::string eigen;         // "3.4.0" and the SIMD instruction sets Eigen compiled for
  std::string lapack;        // the LAPACK/BLAS libraries linked
  std::string blas_loaded;   // the library that provides dgemm in this process
  std::string lapack_loaded; // the library that provides dgees in this process
};

const BuildInfo& build_info();

// "thetad 0.1.0 (git 1a2b3c4d5e6f, Release, GNU 12.2.0)": what `thetad --version` prints.
std::string version_line();

}  // namespace thetad
