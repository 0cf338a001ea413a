#pragma once

#include <cstdint>
#include <string>

#include "experiment/flight.hpp"

namespace thetad {

// How much of the flight the check data holds: `segments` runs of `samples_per_segment`
// consecutive controller samples, spread evenly over the recorded flight.
struct ExportCheckOptions {
  int segments = 10;
  int samples_per_segment = 100;
};

// What `thetad export` writes for one controller (docs/onboard.md): three files by name and text.
struct ExportedController {
  std::string label;
  std::string controller;
  std::string name_space;  // of the header's step and data (the label as an identifier)
  std::string header_file, header;          // LABEL.hpp: the step, its design and the helicopter
  std::string check_data_file, check_data;  // LABEL_check_data.hpp: recorded samples and the library's u
  std::string driver_file, driver;          // LABEL_check.cpp: the check program
  std::uint64_t checksum_double = 0, checksum_float = 0;
  int check_samples = 0;
  std::string recording_diverged;  // why the recording flight ended early; "" if it completed
};

// The controller of `prepared` designed at the flight's initial state (reset at t = 0), as a
// self-contained header, and its check: the flight flown by the library's controller, the
// samples of `check` with the u the library computes on them. Exports θ–D (feedforward none or
// velocity) and the LQR (feedforward none) on the helicopter; throws thetad::Error naming the
// controller and what is exportable otherwise.
ExportedController export_controller(const Flight& flight, PreparedController& prepared,
                                     const ExportCheckOptions& check);

// The label as a C++ identifier: letters, digits and '_' kept, anything else '_', a leading digit
// prefixed.
std::string identifier_of(const std::string& label);

}  // namespace thetad
