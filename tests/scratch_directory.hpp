#pragma once

// A fresh, empty directory for the files one test writes, removed with it. It lies under the
// system's temporary directory and is named after the test program, the running test and the
// process, so that tests run in parallel by ctest never share one.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

namespace thetad::testing {

class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& program) {
    std::string name = program + "_" + std::to_string(::getpid());
    // Outside a test (a suite's set-up) there is no test name: the directory serves the suite.
    if (const auto* test = ::testing::UnitTest::GetInstance()->current_test_info()) name += std::string("_") + test->name();
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;  // a destructor must not throw; a leftover temporary is harmless
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace thetad::testing
