#pragma once

#include <filesystem>

#include <CLI/CLI.hpp>

namespace thetad::app {

struct DesignLqrArguments {
  std::filesystem::path grid;      // YAML/JSON grid (read_lqr_grid); empty: the default envelope
  std::filesystem::path scenario;  // its model options; empty: the resolved preset
  std::filesystem::path out;
};
CLI::App* add_design_lqr_command(CLI::App& app, DesignLqrArguments& arguments);

// thetad design-lqr: trims, linearizations and LQR gains over the grid, saved as the table the
// lqr-scheduled controller loads (`table: FILE`). Progress on stderr, a summary on stdout.
int run_design_lqr(const DesignLqrArguments& arguments);

}  // namespace thetad::app
