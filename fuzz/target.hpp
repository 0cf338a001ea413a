#pragma once

// What every fuzz target checks about the code under test, whatever the input: it returns, or it
// throws thetad::Error with a message that is valid UTF-8 (messages are printed and stored in JSON
// results). Anything else (another exception, a crash, a hang, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad::fuzz {

[[noreturn]] inline void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz finding: %s: %s\n", what, detail.c_str());
  std::abort();
}

// Runs `check` on the input as text; a thetad::Error is an accepted answer to a bad input.
template <class Check>
int run(const std::uint8_t* data, std::size_t size, Check&& check) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check(text);
  } catch (const Error& error) {
    const std::string message = error.what();
    if (message.empty()) finding("an error without a message", "");
    if (invalid_utf8(message) != std::string::npos) finding("an error message that is not UTF-8", message);
  } catch (const std::exception& error) {
    finding("an exception other than thetad::Error", error.what());
  }
  return 0;
}

}  // namespace thetad::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
