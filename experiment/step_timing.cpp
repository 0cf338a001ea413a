#include "experiment/step_timing.hpp"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/error.hpp"
#include "core/sim/run_metrics.hpp"
#include "experiment/provenance.hpp"

namespace thetad {

namespace {

// Flies like the wrapped controller and keeps what every control() call received.
class SampleRecorder final : public Controller {
 public:
  SampleRecorder(std::unique_ptr<Controller> inner, RecordedSamples& samples)
      : inner_(std::move(inner)), samples_(&samples) {}

  std::string name() const override { return inner_->name(); }
  std::unique_ptr<Controller> clone() const override {
    return std::make_unique<SampleRecorder>(inner_->clone(), *samples_);
  }
  void reset(const Eigen::VectorXd& x0, double t0) override { inner_->reset(x0, t0); }
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override {
    samples_->time.push_back(t);
    samples_->measured.emplace_back(measured_state);
    samples_->reference.push_back(reference);
    inner_->control(t, measured_state, reference, u);
  }
  int last_iterations() const override { return inner_->last_iterations(); }

 private:
  std::unique_ptr<Controller> inner_;
  RecordedSamples* samples_;
};

int pin(int requested) {
  if (requested == -2) return -1;
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return -1;
  int cpu = requested;
  if (cpu == -1) {
    for (int c = CPU_SETSIZE - 1; c >= 0 && cpu < 0; --c)
      if (CPU_ISSET(c, &allowed)) cpu = c;
  }
  if (cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))
    throw Error("bench: cannot pin to core " + std::to_string(requested) + ": not one this process may use");
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  if (sched_setaffinity(0, sizeof one, &one) != 0) throw Error("bench: cannot pin to core " + std::to_string(cpu));
  return cpu;
}

// The timed samples: `segments` runs of consecutive samples spread evenly over the recording, each
// after kSettleSamples untimed ones. first[i] is where segment i starts stepping.
struct Plan {
  std::vector<std::size_t> first;
  std::size_t per_segment = 0;
};

Plan plan(std::size_t recorded, const StepTimingOptions& options) {
  if (options.samples < 1 || options.segments < 1)
    throw Error("bench: samples and segments must be >= 1");
  const auto segments = static_cast<std::size_t>(options.segments);
  Plan p;
  p.per_segment = (static_cast<std::size_t>(options.samples) + segments - 1) / segments;
  const std::size_t span = kSettleSamples + p.per_segment;
  if (span * segments > recorded)
    throw Error("bench: the flight recorded " + std::to_string(recorded) + " samples, fewer than the " +
                std::to_string(span * segments) + " that " + std::to_string(segments) + " segments of " +
                std::to_string(p.per_segment) + " timed samples need: fly longer or time fewer samples");
  const std::size_t stride = recorded / segments;
  for (std::size_t i = 0; i < segments; ++i) p.first.push_back(i * stride + (stride - span) / 2);
  return p;
}

// One pass of `controller` over the planned samples from a reset; with `timing`, the time of each
// timed call and its iterations (ControlLaw::last_iterations) added up.
void pass(Controller& controller, const RecordedSamples& samples, const Plan& plan, const Eigen::VectorXd& x0,
          Eigen::VectorXd& u, StepTiming* timing, const std::string& label) {
  controller.reset(x0, samples.time.front());
  for (const std::size_t first : plan.first) {
    for (std::size_t k = first; k < first + kSettleSamples + plan.per_segment; ++k) {
      try {
        const auto start = std::chrono::steady_clock::now();
        controller.control(samples.time[k], samples.measured[k], samples.reference[k], u);
        const auto stop = std::chrono::steady_clock::now();
        if (timing && k >= first + kSettleSamples) {
          timing->nanoseconds.push_back(
              static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count()));
          timing->iterations_mean += controller.last_iterations();
        }
      } catch (const Error& error) {
        throw Error("bench: " + label + " failed on the recorded sample at t = " + std::to_string(samples.time[k]) +
                    " s: " + error.what());
      }
    }
  }
}

// The change of the median between the first and the second half of the passes (`per_pass` calls
// each) in `calls`: a host whose speed drifts during the timing shows it.
double median_drift(const std::vector<double>& calls, std::size_t per_pass) {
  const std::size_t passes = calls.size() / per_pass, half = passes / 2 * per_pass;
  const auto median_of = [](std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return sim::nearest_rank(values, 0.5);
  };
  if (half == 0) return 0.0;
  return std::abs(median_of({calls.begin() + static_cast<std::ptrdiff_t>(half), calls.end()}) -
                  median_of({calls.begin(), calls.begin() + static_cast<std::ptrdiff_t>(half)}));
}

}  // namespace

RecordedSamples record_samples(const Flight& flight, PreparedController& prepared, Progress* progress) {
  RecordedSamples samples;
  samples.recorded_with = prepared.spec.label;
  PreparedController recorder{prepared.spec, std::make_unique<SampleRecorder>(prepared.controller->clone(), samples),
                              prepared.settings, prepared.origin};
  const RunResult run = flight.fly(recorder, progress, "recording with " + prepared.spec.label + ":");
  samples.status = run.summary.status;
  samples.reason = run.summary.reason;
  if (samples.size() == 0)
    throw Error("bench: the recording flight with " + prepared.spec.label + " kept no sample (" + run.summary.reason + ")");
  return samples;
}

StepTimingReport time_steps(std::vector<PreparedController>& controllers, const RecordedSamples& samples,
                            const Eigen::VectorXd& initial_state, Eigen::Index input_dim,
                            const StepTimingOptions& options) {
  if (options.repetitions < 1 || options.warmup_passes < 0)
    throw Error("bench: repetitions must be >= 1 and warm-up passes >= 0");
  const Plan timed = plan(samples.size(), options);
  StepTimingReport report;
  report.options = options;
  report.samples = timed.first.size() * timed.per_segment;
  report.cpu = pin(options.cpu);
  Eigen::VectorXd u(input_dim);
  for (auto& prepared : controllers) {
    report.controllers.push_back({prepared.spec.label, prepared.spec.controller, {}, 0, 0, 0, 0, 0, 0, 0, 0,
                                  RealTimeVerdict::not_capable});
    report.controllers.back().nanoseconds.reserve(report.samples * static_cast<std::size_t>(3 * options.repetitions));
  }
  for (int warmup = 0; warmup < options.warmup_passes; ++warmup)
    for (auto& prepared : controllers) pass(*prepared.controller, samples, timed, initial_state, u, nullptr, prepared.spec.label);
  const HostSnapshot before = host_snapshot();
  // Interleaved: repetition r of every controller before repetition r + 1 of any.
  const auto repeat = [&] {
    for (std::size_t c = 0; c < controllers.size(); ++c)
      pass(*controllers[c].controller, samples, timed, initial_state, u, &report.controllers[c], controllers[c].spec.label);
    ++report.repetitions;
  };
  while (report.repetitions < options.repetitions) repeat();
  const auto settled = [&] {
    return std::all_of(report.controllers.begin(), report.controllers.end(), [&](StepTiming& timing) {
      timing.median_drift = median_drift(timing.nanoseconds, report.samples);
      return settled_median(timing);
    });
  };
  while (!(report.stable = settled()) && report.repetitions < 3 * options.repetitions) repeat();
  report.host = host_conditions(before, host_snapshot(), report.cpu);
  const double budget_ns = options.budget_seconds * 1e9;
  for (StepTiming& timing : report.controllers) {
    std::vector<double> sorted = timing.nanoseconds;
    std::sort(sorted.begin(), sorted.end());
    timing.median = sim::nearest_rank(sorted, 0.5);
    timing.median_drift = median_drift(timing.nanoseconds, report.samples);
    timing.p10 = sim::nearest_rank(sorted, 0.1);
    timing.p90 = sim::nearest_rank(sorted, 0.9);
    timing.p99 = sim::nearest_rank(sorted, 0.99);
    timing.max = sorted.back();
    timing.overruns = static_cast<std::size_t>(sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), budget_ns));
    timing.iterations_mean /= static_cast<double>(sorted.size());  // the sum, until here
    timing.verdict = real_time_verdict(timing.p99, static_cast<double>(timing.overruns) / static_cast<double>(sorted.size()),
                                       budget_ns);
  }
  return report;
}

RealTimeVerdict real_time_verdict(double p99, double overrun_share, double budget) {
  if (p99 > budget) return RealTimeVerdict::not_capable;
  if (p99 <= kCapableShare * budget && overrun_share <= kOverrunShare) return RealTimeVerdict::capable;
  return RealTimeVerdict::marginal;
}

bool settled_median(const StepTiming& timing) {
  std::vector<double> sorted = timing.nanoseconds;
  std::sort(sorted.begin(), sorted.end());
  return timing.median_drift <= std::max(kStableDrift * sim::nearest_rank(sorted, 0.5), kTimerResolutionNs);
}

const char* verdict_name(RealTimeVerdict verdict) {
  switch (verdict) {
    case RealTimeVerdict::capable: return "capable";
    case RealTimeVerdict::marginal: return "marginal";
    case RealTimeVerdict::not_capable: return "not capable";
  }
  return "unknown";
}

std::string step_timing_table(const StepTimingReport& report) {
  std::size_t width = std::string("controller").size();
  for (const auto& timing : report.controllers) width = std::max(width, timing.label.size());
  const int w = static_cast<int>(width);
  const double budget_us = report.options.budget_seconds * 1e6;
  std::string text;
  char line[320];
  std::snprintf(line, sizeof line, "%-*s %10s %10s %10s %10s %10s %9s %9s %6s  %s\n", w, "controller", "median us",
                "p10 us", "p90 us", "p99 us", "max us", "budget", "overruns", "iters", "one core at the period");
  text += line;
  for (const auto& t : report.controllers) {
    std::snprintf(line, sizeof line, "%-*s %10.2f %10.2f %10.2f %10.2f %10.2f %8.1f%% %9zu %6.2f  %s\n", w,
                  t.label.c_str(), t.median * 1e-3, t.p10 * 1e-3, t.p90 * 1e-3, t.p99 * 1e-3, t.max * 1e-3,
                  100.0 * t.median * 1e-3 / budget_us, t.overruns, t.iterations_mean, verdict_name(t.verdict));
    text += line;
  }
  std::snprintf(line, sizeof line,
                "%zu timed steps (%d runs of consecutive 1 kHz samples spread over the flight) x %d repetitions per "
                "controller (interleaved, after %d warm-up pass%s), %s; budget: the %.3g ms controller period; iters: "
                "the controller's iterations per step (fixed-point passes; 0: closed form).\n",
                report.samples, report.options.segments, report.repetitions, report.options.warmup_passes,
                report.options.warmup_passes == 1 ? "" : "es",
                report.cpu >= 0 ? ("pinned to core " + std::to_string(report.cpu)).c_str() : "not pinned",
                report.options.budget_seconds * 1e3);
  text += line;
  std::snprintf(line, sizeof line,
                "Verdict: capable when p99 <= %.0f %% of the period and at most %.1f %% of the calls overrun it; not "
                "capable when p99 overruns it; marginal in between.\n",
                100.0 * kCapableShare, 100.0 * kOverrunShare);
  text += line;
  const HostConditions& host = report.host;
  std::snprintf(line, sizeof line,
                "Host: %s, governor %s; load %.2f before, %.2f after; steal %.1f %%, busiest other core %.1f %%, "
                "timed thread waiting %.1f %%.\n",
                host.cpu_model.c_str(), host.governor.c_str(), host.load_before, host.load_after, 100.0 * host.steal,
                100.0 * host.other_cores_busy, 100.0 * host.own_wait);
  text += line;
  for (const auto& warning : host.warnings) text += "WARNING: the host was loaded: " + warning + "; the figures and verdicts are not the controllers' alone.\n";
  for (const auto& t : report.controllers) {
    if (settled_median(t)) continue;
    std::snprintf(line, sizeof line,
                  "WARNING: %s's median did not settle: it moved by %.3f us (%.1f %%) between the first and the second "
                  "half of %d passes.\n",
                  t.label.c_str(), t.median_drift * 1e-3, 100.0 * t.median_drift / t.median, report.repetitions);
    text += line;
  }
  return text;
}

nlohmann::ordered_json to_json(const StepTimingReport& report) {
  nlohmann::ordered_json j;
  j["format"] = kBenchFormat;
  j["format_version"] = kBenchFormatVersion;
  j["timed_steps_per_pass"] = report.samples;
  j["segments"] = report.options.segments;
  j["repetitions"] = report.repetitions;
  j["medians_stable"] = report.stable;
  j["warmup_passes"] = report.options.warmup_passes;
  j["cpu"] = report.cpu;
  j["budget_s"] = report.options.budget_seconds;
  j["verdict_rule"] = {{"capable_p99_share", kCapableShare},
                       {"overrun_share", kOverrunShare},
                       {"stable_median_drift", kStableDrift},
                       {"timer_resolution_ns", kTimerResolutionNs}};
  j["host"] = to_json(report.host);
  j["controllers"] = nlohmann::ordered_json::array();
  for (const auto& t : report.controllers) {
    j["controllers"].push_back({{"label", t.label},
                                {"controller", t.controller},
                                {"calls", t.nanoseconds.size()},
                                {"step_time_median_us", t.median * 1e-3},
                                {"step_time_p10_us", t.p10 * 1e-3},
                                {"step_time_p90_us", t.p90 * 1e-3},
                                {"step_time_p99_us", t.p99 * 1e-3},
                                {"step_time_max_us", t.max * 1e-3},
                                {"overruns", t.overruns},
                                {"median_drift_ns", t.median_drift},
                                {"iterations_mean", t.iterations_mean},
                                {"budget_share_median", t.median * 1e-9 / report.options.budget_seconds},
                                {"verdict", verdict_name(t.verdict)},
                                {"real_time_capable", t.verdict == RealTimeVerdict::capable}});
  }
  return j;
}

nlohmann::ordered_json bench_json(const Flight& flight, const RecordedSamples& samples, const StepTimingReport& report) {
  nlohmann::ordered_json j = to_json(report);
  Provenance provenance = flight.provenance();
  stamp_host_and_time(provenance);
  j["recorded_with"] = samples.recorded_with;
  j["recording_status"] = sim::status_name(samples.status);
  j["recording_reason"] = samples.reason;
  j["provenance"] = to_json(provenance);
  return j;
}

}  // namespace thetad
