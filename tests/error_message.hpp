#pragma once

// The message of the thetad::Error a call must throw (a test failure, and "", when it throws none).
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace thetad::testing {

inline std::string error_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no thetad::Error";
  return {};
}

}  // namespace thetad::testing
