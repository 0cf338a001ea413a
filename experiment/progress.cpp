#include "experiment/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace thetad {

Progress::Mode Progress::mode_for_stderr(bool quiet) {
  if (quiet) return Mode::quiet;
  return isatty(fileno(stderr)) == 1 && std::getenv("CI") == nullptr ? Mode::live : Mode::lines;
}

std::chrono::duration<double> progress_interval() {
  if (const char* text = std::getenv("THETAD_PROGRESS_INTERVAL")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && seconds >= 0.0) return std::chrono::duration<double>(seconds);
  }
  return std::chrono::duration<double>(10.0);
}

Progress::Progress(Mode mode, ProgressObserver observer)
    : mode_(mode), observer_(std::move(observer)), interval_(progress_interval()) {}

std::string format_duration(double seconds) {
  char text[48];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 3600.0) {
    std::snprintf(text, sizeof text, "%d min %02d s", static_cast<int>(seconds / 60.0), static_cast<int>(seconds) % 60);
  } else {
    std::snprintf(text, sizeof text, "%d h %02d min", static_cast<int>(seconds / 3600.0),
                  static_cast<int>(seconds / 60.0) % 60);
  }
  return text;
}

std::string Progress::what() const {
  char text[96];
  std::snprintf(text, sizeof text, "%g %s", total_, unit_.empty() ? "s simulated" : unit_.c_str());
  return text;
}

std::string Progress::status(double done) const {
  const double wall = std::chrono::duration<double>(Clock::now() - started_).count();
  const double rate = wall > 0.0 ? done / wall : 0.0;  // units per wall second
  char text[160];
  if (rate > 0.0 && unit_.empty()) {
    std::snprintf(text, sizeof text, "%3.0f %% (%.1f of %s, %.2fx real time, ETA %s)", 100.0 * done / total_, done,
                  what().c_str(), rate, format_duration((total_ - done) / rate).c_str());
  } else if (rate > 0.0) {
    std::snprintf(text, sizeof text, "%3.0f %% (%g of %s, at most %s left)", 100.0 * done / total_, done,
                  what().c_str(), format_duration((total_ - done) / rate).c_str());
  } else {
    std::snprintf(text, sizeof text, "%3.0f %% (%g of %s)", 100.0 * done / total_, done, what().c_str());
  }
  return text;
}

void Progress::start(const std::string& label, double total, const std::string& unit) {
  label_ = label;
  unit_ = unit;
  total_ = total;
  started_ = last_shown_ = Clock::now();
  if (observer_) observer_({label_, 0.0, total_, unit_});
  if (mode_ == Mode::lines)
    std::fprintf(stderr, "%s %s (%s)\n", label_.c_str(), unit_.empty() ? "flying" : "started", what().c_str());
}

void Progress::update(double done, const std::string& note) {
  if (observer_) observer_({label_, done, total_, unit_});
  if (mode_ == Mode::quiet) return;
  const auto now = Clock::now();
  const auto since = now - last_shown_;
  if (mode_ == Mode::live && since >= std::chrono::milliseconds(200)) {
    std::fprintf(stderr, "\r\033[K%s %s%s%s", label_.c_str(), status(done).c_str(), note.empty() ? "" : " ", note.c_str());
    last_shown_ = now;
  } else if (mode_ == Mode::lines && since >= interval_) {
    std::fprintf(stderr, "%s %s%s%s\n", label_.c_str(), status(done).c_str(), note.empty() ? "" : " ", note.c_str());
    last_shown_ = now;
  }
}

void Progress::finish(const std::string& outcome) {
  if (observer_) observer_({label_, total_, total_, unit_});
  if (mode_ == Mode::quiet) return;
  if (mode_ == Mode::live) std::fprintf(stderr, "\r\033[K");
  std::fprintf(stderr, "%s %s\n", label_.c_str(), outcome.c_str());
}

void Progress::note(const std::string& line) {
  if (mode_ != Mode::quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace thetad
