#include "experiment/host_conditions.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace thetad {

namespace {

std::string first_line(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    return colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1));
  }
  return "unknown";
}

std::string governor(int cpu) {
  const std::string value =
      first_line("/sys/devices/system/cpu/cpu" + std::to_string(std::max(cpu, 0)) + "/cpufreq/scaling_governor");
  return value.empty() ? "unknown" : value;
}

double share(double part, double whole) { return whole > 0.0 ? part / whole : 0.0; }

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %%", 100.0 * fraction);
  return text;
}

}  // namespace

HostSnapshot host_snapshot() {
  HostSnapshot snapshot;
  std::ifstream stat("/proc/stat");
  for (std::string line; std::getline(stat, line);) {
    // "cpuN user nice system idle iowait irq softirq steal guest guest_nice"; "cpu " is the sum.
    if (line.rfind("cpu", 0) != 0 || line.size() < 4 || line[3] == ' ') continue;
    std::istringstream fields(line.substr(line.find(' ')));
    double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    fields >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
    const double busy = user + nice + system + irq + softirq + steal;
    snapshot.cpus.push_back({busy, busy + idle + iowait, steal});
  }
  std::istringstream(first_line("/proc/loadavg")) >> snapshot.load_average;
  double running = 0.0;
  std::istringstream(first_line("/proc/thread-self/schedstat")) >> running >> snapshot.wait_ns;
  snapshot.wall_ns = static_cast<double>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
  return snapshot;
}

HostConditions host_conditions(const HostSnapshot& before, const HostSnapshot& after, int pinned_cpu) {
  HostConditions c;
  c.cpu_model = cpu_model();
  c.governor = governor(pinned_cpu);
  c.pinned_cpu = pinned_cpu;
  c.load_before = before.load_average;
  c.load_after = after.load_average;
  double steal = 0.0, total = 0.0;
  const std::size_t cpus = std::min(before.cpus.size(), after.cpus.size());
  for (std::size_t i = 0; i < cpus; ++i) {
    const double busy = after.cpus[i].busy - before.cpus[i].busy, all = after.cpus[i].total - before.cpus[i].total;
    steal += after.cpus[i].steal - before.cpus[i].steal;
    total += all;
    if (static_cast<int>(i) != pinned_cpu) c.other_cores_busy = std::max(c.other_cores_busy, share(busy, all));
  }
  c.steal = share(steal, total);
  c.own_wait = share(after.wait_ns - before.wait_ns, after.wall_ns - before.wall_ns);
  if (c.other_cores_busy > HostConditions::kMaxOtherCoresBusy)
    c.warnings.push_back("another core was " + percent(c.other_cores_busy) + " busy during the timing");
  if (c.own_wait > HostConditions::kMaxOwnWait)
    c.warnings.push_back("the timed thread waited for its core " + percent(c.own_wait) + " of the time (another "
                         "process shared it)");
  if (c.steal > HostConditions::kMaxSteal)
    c.warnings.push_back("the hypervisor took " + percent(c.steal) + " of the cores' time (steal)");
  return c;
}

nlohmann::ordered_json to_json(const HostConditions& c) {
  nlohmann::ordered_json j;
  j["cpu_model"] = c.cpu_model;
  j["governor"] = c.governor;
  j["pinned_cpu"] = c.pinned_cpu;
  j["load_average_before"] = c.load_before;
  j["load_average_after"] = c.load_after;
  j["steal_share"] = c.steal;
  j["other_cores_busy_share"] = c.other_cores_busy;
  j["own_wait_share"] = c.own_wait;
  j["loaded"] = c.loaded();
  j["warnings"] = c.warnings;
  return j;
}

}  // namespace thetad
