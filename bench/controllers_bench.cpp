// One control step of every registered controller on the same states: those the simulator handed
// the θ–D controller in a closed-loop run of scenario I (all disturbances, its seed), cycled in
// their order, so that a warm-started SDRE sees realistic step-to-step changes and no controller
// is timed on one cached state. Every controller in the registry runs by its name with its
// defaults, as `thetad run` flies it (a controller registered later is timed without an edit
// here). Besides, built directly: θ–D with N = 1 … 4 terms and 1 (one-step lag) or 3 (exact Ω,
// docs/model.md §6.2) fixed-point passes; SDRE cold (solve_care: the matrix sign function, Schur as
// fallback) and warm (Newton–Kleinman from the last P) with the same passes; θ–D's 3-term step on
// dynamic-size types; the plant's F, B; as a reference for the Riccati solver, the SDRE step
// with SLICOT's SB02MD in place of solve_care; and the exported θ–D, LQR and capped SDRE steps
// (docs/onboard.md) in float and double, beside the registry's `theta-d` and `lqr` rows and the
// library's capped SDRE (`sdre-capped`, scenarios/sdre-capped.settings.yaml) on the same states.
//
// The fixed-point tolerance is 0 in those θ–D and SDRE rows, so that "3 passes" always means 3:
// the cost of the variant, not of how fast one trajectory happens to converge. The registry's
// rows stop at their default tolerance (1e-6): their `passes` counter says how many ran.

#include <benchmark/benchmark.h>

#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "bench/benchmark_main.hpp"
#include "bench/slicot.hpp"
#include "controllers/registry.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/sim/recording_law.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "scenarios/scenario.hpp"
#include "tests/controllers/every_pass_settings.hpp"
// Exported by the build (export/CMakeLists.txt) at scenario I's start, where the registry's rows
// are designed: the paper's θ–D (namespace theta_d), the hover LQR (namespace lqr) and the capped
// SDRE (namespace sdre_capped).
#include "lqr.hpp"
#include "sdre-capped.hpp"
#include "theta-d.hpp"

namespace {

namespace heli = thetad::heli;

// The recorded window: 2 s (2000 samples at 1 kHz) inside the figure 8 of scenario I.
constexpr double kRecordFrom = 13.0;
constexpr double kRecordTo = 15.0;

using Sample = thetad::sim::ControlSample;

struct Recording {
  thetad::Scenario scenario;
  heli::Helicopter model;  // the controllers' nominal model (docs/model.md §11)
  std::vector<Sample> samples;

  Recording()
      : scenario(thetad::load_scenario(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml")),
        model(heli::Parameters::nominal(), scenario.model_options) {
    thetad::sim::SimulationSettings settings = scenario.simulation_settings();
    settings.duration = kRecordTo;
    settings.measure_compute_time = false;
    const auto flown = make("theta-d", YAML::Node());
    thetad::sim::RecordingLaw law(*flown, kRecordFrom, samples);
    const auto run = thetad::sim::simulate(law, scenario.trajectory, scenario.initial_state, settings,
                                           heli::Parameters::nominal(), scenario.model_options);
    if (run.summary.status != thetad::sim::RunStatus::completed)
      throw std::runtime_error("controllers_bench: the recording run diverged: " + run.summary.reason);
  }

  std::unique_ptr<thetad::Controller> make(const std::string& name, const YAML::Node& settings) const {
    return thetad::ControllerRegistry::instance().make(name, settings,
                                                       thetad::ControllerContext{model, scenario.initial_state, 0.0});
  }
};

// Recorded on first use, so that listing the benchmarks costs nothing.
const Recording& recording() {
  static const Recording instance;
  return instance;
}

// Times controller.control() on the recorded samples in order, from the second on.
void time_steps(benchmark::State& state, thetad::Controller& controller) {
  const Recording& r = recording();
  controller.reset(r.scenario.initial_state, 0.0);
  Eigen::VectorXd u(heli::kInputDim);
  // One untimed step: the SDRE's first sample is always cold.
  controller.control(r.samples[0].t, r.samples[0].state, r.samples[0].reference, u);
  std::size_t k = 1;
  double passes = 0.0;
  for (auto _ : state) {
    const Sample& s = r.samples[k];
    controller.control(s.t, s.state, s.reference, u);
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
    passes += controller.last_iterations();
    if (++k == r.samples.size()) k = 0;
  }
  state.counters["passes"] = benchmark::Counter(passes, benchmark::Counter::kAvgIterations);
  state.counters["states"] = static_cast<double>(r.samples.size());
}

// A controller from the registry with its defaults, built once: Google Benchmark calls a function
// several times, and lqr-scheduled designs its table of trims (seconds) when it is built.
void registered_step(benchmark::State& state, const std::string& name, const std::string& settings) {
  static std::map<std::string, std::unique_ptr<thetad::Controller>> built;
  auto& controller = built[name + settings];
  if (!controller) controller = recording().make(name, YAML::Load(settings));
  time_steps(state, *controller);
}

// The library's capped SDRE with the settings the exported one was exported with.
const char* const kCappedSettings = "{mode: capped, newton_iterations: 2}";

// The exported step's state as the library's controller leaves it after the untimed first sample
// (time_steps()): the capped SDRE's P, which the exported reset() sets to the design point's,
// far from the recorded window's states; nothing for θ–D and the LQR.
template <class StepState>
void resume_as_library(StepState& step_state) {
  if constexpr (requires { step_state.value; }) {
    const Recording& r = recording();
    const auto library = r.make("sdre", YAML::Load(kCappedSettings));
    library->reset(r.scenario.initial_state, 0.0);
    Eigen::VectorXd u(heli::kInputDim);
    library->control(r.samples[0].t, r.samples[0].state, r.samples[0].reference, u);
    const Eigen::MatrixXd& P = dynamic_cast<const thetad::SdreController&>(*library).last_value_matrix();
    for (int e = 0; e < heli::kStateDim * heli::kStateDim; ++e)
      step_state.value[e] = P(e / heli::kStateDim, e % heli::kStateDim);
    for (int k = 0; k < heli::kInputDim; ++k) step_state.applied[k] = u(k);
  }
}

void theta_d_step(benchmark::State& state, int terms, int passes, bool fixed_size) {
  const Recording& r = recording();
  auto s = thetad::testing::every_pass_settings<thetad::ThetaDSettings>(r.model, passes);
  s.terms = terms;
  s.fixed_size = fixed_size;
  thetad::ThetaDController controller(r.model, s);
  time_steps(state, controller);
}

// An exported step in Scalar on the recorded samples in order, from the second on, as time_steps()
// times a library controller; the samples are converted to Scalar beforehand, untimed.
template <class Scalar, class StepState, void (*reset)(StepState&),
          thetad_onboard::Status (*step)(StepState&, Scalar, const Scalar*, const thetad_onboard::Reference<Scalar>&, Scalar*)>
void exported_step(benchmark::State& state) {
  struct Converted {
    Scalar t, x[heli::kStateDim];
    thetad_onboard::Reference<Scalar> reference;
  };
  const Recording& r = recording();
  std::vector<Converted> samples(r.samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k].t = Scalar(r.samples[k].t);
    for (int i = 0; i < heli::kStateDim; ++i) samples[k].x[i] = Scalar(r.samples[k].state(i));
    for (int i = 0; i < 3; ++i) {
      samples[k].reference.position[i] = Scalar(r.samples[k].reference.position(i));
      samples[k].reference.integral[i] = Scalar(r.samples[k].reference.integral(i));
      samples[k].reference.velocity[i] = Scalar(r.samples[k].reference.velocity(i));
      samples[k].reference.acceleration[i] = Scalar(r.samples[k].reference.acceleration(i));
    }
  }
  const auto step_state = std::make_unique<StepState>();  // tens of KiB: not on the stack
  reset(*step_state);
  Scalar u[heli::kInputDim];
  if constexpr (requires { step_state->value; }) {
    resume_as_library(*step_state);
  } else {
    step(*step_state, samples[0].t, samples[0].x, samples[0].reference, u);
  }
  std::size_t k = 1;
  double passes = 0.0;
  for (auto _ : state) {
    const Converted& s = samples[k];
    if (step(*step_state, s.t, s.x, s.reference, u) != thetad_onboard::Status::ok) {
      state.SkipWithError("the exported step failed");
      break;
    }
    benchmark::DoNotOptimize(u);
    benchmark::ClobberMemory();
    if constexpr (requires { step_state->iterations; }) passes += step_state->iterations;
    if (++k == samples.size()) k = 0;
  }
  state.counters["passes"] = benchmark::Counter(passes, benchmark::Counter::kAvgIterations);
}

template <class Scalar>
void register_exported(const std::string& scalar) {
  benchmark::RegisterBenchmark(("exported/theta-d/" + scalar).c_str(),
                               exported_step<Scalar, theta_d::State<Scalar>, theta_d::reset<Scalar>, theta_d::step<Scalar>>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("exported/lqr/" + scalar).c_str(),
                               exported_step<Scalar, lqr::State<Scalar>, lqr::reset<Scalar>, lqr::step<Scalar>>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(
      ("exported/sdre-capped/" + scalar).c_str(),
      exported_step<Scalar, sdre_capped::State<Scalar>, sdre_capped::reset<Scalar>, sdre_capped::step<Scalar>>)
      ->Unit(benchmark::kMicrosecond);
}

// F(x), B(x) at the recorded states and inputs, rotor speed from T_mr included: the whole sdc(),
// and what a controller's step calls (sdc_constant() once, then sdc_varying()).
void sdc_evaluation(benchmark::State& state, bool varying_only) {
  const Recording& r = recording();
  Eigen::MatrixXd F(heli::kStateDim, heli::kStateDim), B(heli::kStateDim, heli::kInputDim);
  r.model.sdc_constant(F, B);
  std::size_t k = 0;
  for (auto _ : state) {
    const Sample& sample = r.samples[k];
    if (varying_only) r.model.sdc_varying(sample.state, sample.input, F, B);
    else r.model.sdc(sample.state, sample.input, F, B);
    benchmark::DoNotOptimize(F.data());
    benchmark::DoNotOptimize(B.data());
    benchmark::ClobberMemory();
    if (++k == r.samples.size()) k = 0;
  }
}

void sdre_step(benchmark::State& state, thetad::SdreSettings::Mode mode, int passes) {
  const Recording& r = recording();
  auto s = thetad::testing::every_pass_settings<thetad::SdreSettings>(r.model, passes);
  s.mode = mode;
  thetad::SdreController controller(r.model, s);
  time_steps(state, controller);
}

// The SDRE's one-pass step (F, B at the recorded input, CARE, u = −R⁻¹BᵀPv) with SB02MD as the
// CARE solver: Laub's method, general scaling, G = B R⁻¹ Bᵀ formed per step as SB02MD needs it.
void sdre_step_sb02md(benchmark::State& state) {
  const Recording& r = recording();
  const int n = heli::kStateDim;
  const Eigen::MatrixXd Q = r.model.design_defaults().state_weights.asDiagonal();
  const Eigen::MatrixXd R = r.model.design_defaults().input_weights.asDiagonal();
  const Eigen::LLT<Eigen::MatrixXd> R_factor(R);
  thetad::bench::Sb02md sb02md(n);
  Eigen::MatrixXd F(n, n), B(n, heli::kInputDim), g(n, n), x(n, n);
  Eigen::VectorXd v(n), u(heli::kInputDim);
  int info = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    const Sample& sample = r.samples[k];
    r.model.sdc(sample.state, sample.input, F, B);
    r.model.tracking_vector(sample.state, sample.reference, v);
    g.noalias() = B * R_factor.solve(B.transpose());
    info = sb02md.solve(F, g, Q, x);
    if (info != 0) break;
    u.noalias() = -R_factor.solve(B.transpose() * (x * v));
    benchmark::DoNotOptimize(u.data());
    if (++k == r.samples.size()) k = 0;
  }
  if (info != 0) state.SkipWithError(("SB02MD info " + std::to_string(info)).c_str());
}

void register_benchmarks() {
  using Mode = thetad::SdreSettings::Mode;
  for (const int passes : {1, 3}) {
    const std::string suffix = "/passes:" + std::to_string(passes);
    for (const int terms : {1, 2, 3, 4})
      benchmark::RegisterBenchmark(("theta-d/terms:" + std::to_string(terms) + suffix).c_str(), theta_d_step, terms,
                                   passes, true)
          ->Unit(benchmark::kMicrosecond);
    // The same step on dynamic-size types, as any plant other than the 18 × 5 helicopter runs.
    benchmark::RegisterBenchmark(("theta-d-dynamic-size/terms:3" + suffix).c_str(), theta_d_step, 3, passes, false)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("sdre-cold" + suffix).c_str(), sdre_step, Mode::cold, passes)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("sdre-warm" + suffix).c_str(), sdre_step, Mode::warm, passes)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("sdre-sb02md/passes:1", sdre_step_sb02md)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("sdc", sdc_evaluation, false)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("sdc-varying", sdc_evaluation, true)->Unit(benchmark::kMicrosecond);
  register_exported<float>("float");
  register_exported<double>("double");
  for (const std::string& name : thetad::ControllerRegistry::instance().names())
    benchmark::RegisterBenchmark(name.c_str(), registered_step, name, "{}")->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("sdre-capped", registered_step, "sdre", kCappedSettings)->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) { return thetad::bench::run_benchmarks(argc, argv, register_benchmarks); }
