#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace thetad {

// What the host was doing while a timing ran, from /proc (Linux): a wall-clock figure is worth
// only as much as the machine's quiet, so `thetad bench` records it beside its figures and warns
// when the host was loaded instead of letting a verdict flip silently.

// The counters read at one moment.
struct HostSnapshot {
  struct Cpu {
    double busy = 0.0;   // jiffies not idle nor waiting for I/O (steal included)
    double total = 0.0;  // all jiffies
    double steal = 0.0;  // taken by the hypervisor for other guests
  };
  std::vector<Cpu> cpus;      // per core, as /proc/stat numbers them
  double load_average = 0.0;  // 1-minute
  double wait_ns = 0.0;       // this thread's time runnable but not running (/proc/thread-self/schedstat)
  double wall_ns = 0.0;       // steady clock
};
HostSnapshot host_snapshot();

struct HostConditions {
  std::string cpu_model;  // /proc/cpuinfo's "model name"
  std::string governor;   // the pinned core's frequency governor; "unknown" where the host does not say (VMs)
  int pinned_cpu = -1;
  double load_before = 0.0, load_after = 0.0;  // 1-minute load averages
  double steal = 0.0;                // share of all cores' time the hypervisor took during the timing
  double other_cores_busy = 0.0;     // the busiest core but the pinned one, share of its time
  double own_wait = 0.0;             // share of the timing's wall time this thread waited to run
  std::vector<std::string> warnings;  // each condition beyond its threshold, in words

  bool loaded() const { return !warnings.empty(); }

  // Thresholds beyond which a timing counts as taken on a loaded host. Measured over the timing
  // itself: the load average, recorded too, lags by a minute and counts this process.
  static constexpr double kMaxSteal = 0.02;
  static constexpr double kMaxOtherCoresBusy = 0.25;
  static constexpr double kMaxOwnWait = 0.01;
};

// The conditions between two snapshots of a timing pinned to `pinned_cpu` (-1: not pinned, then
// every core counts as another).
HostConditions host_conditions(const HostSnapshot& before, const HostSnapshot& after, int pinned_cpu);
nlohmann::ordered_json to_json(const HostConditions& conditions);

}  // namespace thetad
