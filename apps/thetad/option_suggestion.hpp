#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace thetad::app {

// For arguments `app` did not expect: " (did you mean --scenario?)" when one of them is a long
// option within two edits of an option of the subcommand being parsed (else of `app`), or of
// that subcommand's own subcommands' names; "" otherwise.
std::string option_suggestion(const CLI::App& app);

}  // namespace thetad::app
