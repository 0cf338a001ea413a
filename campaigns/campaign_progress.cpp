#include "campaigns/campaign_progress.hpp"

#include <cstdio>
#include <utility>

namespace thetad {

CampaignProgress::CampaignProgress(Progress::Mode mode, std::string name, std::int64_t total, std::int64_t done,
                                   ProgressObserver observer)
    : mode_(mode),
      name_(std::move(name)),
      observer_(std::move(observer)),
      total_(total),
      stored_(done),
      interval_(progress_interval()),
      started_(Clock::now()),
      last_shown_(started_) {
  notify();
  if (mode_ == Progress::Mode::quiet) return;
  std::fprintf(stderr, "%s: %lld runs, %lld already stored, %lld to fly\n", name_.c_str(),
               static_cast<long long>(total_), static_cast<long long>(stored_),
               static_cast<long long>(total_ - stored_));
}

std::string CampaignProgress::status() const {
  const double wall = std::chrono::duration<double>(Clock::now() - started_).count();
  const double rate = wall > 0.0 ? static_cast<double>(flown_) / wall : 0.0;
  const std::int64_t done = stored_ + flown_;
  char text[256];
  std::snprintf(text, sizeof text, "%s: %lld / %lld runs (%.0f %%), %.2f runs/s, ETA %s, %lld not completed", name_.c_str(),
                static_cast<long long>(done), static_cast<long long>(total_),
                total_ > 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0, rate,
                rate > 0.0 ? format_duration(static_cast<double>(total_ - done) / rate).c_str() : "unknown",
                static_cast<long long>(not_completed_));
  return text;
}

void CampaignProgress::notify() const {
  static const std::string unit = "runs";
  if (observer_) observer_({name_, static_cast<double>(stored_ + flown_), static_cast<double>(total_), unit});
}

void CampaignProgress::add(bool completed) {
  ++flown_;
  if (!completed) ++not_completed_;
  notify();
  if (mode_ == Progress::Mode::quiet) return;
  const auto now = Clock::now();
  if (mode_ == Progress::Mode::live && now - last_shown_ >= std::chrono::milliseconds(200)) {
    std::fprintf(stderr, "\r\033[K%s", status().c_str());
    last_shown_ = now;
  } else if (mode_ == Progress::Mode::lines && now - last_shown_ >= interval_) {
    std::fprintf(stderr, "%s\n", status().c_str());
    last_shown_ = now;
  }
}

void CampaignProgress::finish() {
  if (mode_ == Progress::Mode::quiet) return;
  if (mode_ == Progress::Mode::live) std::fprintf(stderr, "\r\033[K");
  std::fprintf(stderr, "%s (%s wall)\n", status().c_str(),
               format_duration(std::chrono::duration<double>(Clock::now() - started_).count()).c_str());
}

}  // namespace thetad
