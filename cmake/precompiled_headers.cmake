# The third-party and standard headers that most units include, parsed once into a precompiled
# header per kind of unit instead of in every unit (docs/performance-log.md, 2026-12-02: it saves
# 8 % of the libraries' compile; most of the rest is optimizing Eigen's kernels). Only headers from outside the
# project: a change to the project's own headers must not rebuild them. GCC uses a precompiled
# header only with the options it was built with (-O level, -fPIC or -fPIE, sanitizers), so each
# kind of target that shares one has the same options; where they differ, GCC falls back to the
# text of the header, slower and still correct.
set(THETAD_COMMON_HEADERS
  <algorithm> <array> <cmath> <cstddef> <filesystem> <fstream> <functional> <limits> <map> <memory>
  <optional> <random> <sstream> <stdexcept> <string> <utility> <vector>
  <Eigen/Dense> <nlohmann/json.hpp>)

# The libraries' header, built by a target of its own with the libraries' options (thetad_core's
# public ones: the sanitizers or -march=native when those are on) and no library's private
# definitions: Ipopt's HAVE_CSTDDEF on thetad_core would make GCC refuse it in the other libraries.
add_library(thetad_library_pch OBJECT ${CMAKE_CURRENT_LIST_DIR}/precompiled_header.cpp)
target_link_libraries(thetad_library_pch PRIVATE Eigen3::Eigen nlohmann_json::nlohmann_json thetad_warnings)
target_compile_options(thetad_library_pch PRIVATE $<TARGET_PROPERTY:thetad_core,INTERFACE_COMPILE_OPTIONS>)
target_precompile_headers(thetad_library_pch PRIVATE ${THETAD_COMMON_HEADERS} <yaml-cpp/yaml.h>)

function(thetad_library_precompiled_headers target)
  target_precompile_headers(${target} REUSE_FROM thetad_library_pch)
endfunction()
