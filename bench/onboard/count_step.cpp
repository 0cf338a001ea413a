// Instructions per exported step (scripts/onboard_counts.sh, docs/onboard.md "Counted"): every
// sample of an exported controller's check data fed in order to its step in THETAD_COUNT_SCALAR,
// each run of samples from the input applied before it, as the check program feeds them, inside
// run_steps() between two calls of count_mark(): callgrind collects run_steps() on x86; under qemu
// the script counts the instructions executed between the marks. Samples are converted to the
// scalar type beforehand. The script defines THETAD_EXPORTED_HEADER, THETAD_CHECK_DATA (quoted
// paths) and THETAD_EXPORTED_NAMESPACE.
#include <cstdio>

#include THETAD_EXPORTED_HEADER
#include THETAD_CHECK_DATA

namespace exported = THETAD_EXPORTED_NAMESPACE;
#define THETAD_COUNT_CONCATENATE(a, b) a##b
#define THETAD_COUNT_CHECK(name) THETAD_COUNT_CONCATENATE(name, _check)
namespace check = THETAD_COUNT_CHECK(THETAD_EXPORTED_NAMESPACE);

namespace {

using Scalar = THETAD_COUNT_SCALAR;
constexpr int kN = thetad_onboard::kStates, kM = thetad_onboard::kInputs;

exported::State<Scalar> state;  // static, as on a board
Scalar times[check::kSamples], measured[check::kSamples][kN], applied[check::kSegments][kM], input[kM];
thetad_onboard::Reference<Scalar> references[check::kSamples];
int failures = 0;

// The script finds this function by name; the asm keeps it from being merged or removed.
[[gnu::noinline]] void count_mark() { asm volatile("" ::: "memory"); }

// The fixed-point passes of a θ–D step; the LQR has none.
template <class StepState>
int passes_of(const StepState& s) {
  if constexpr (requires { s.iterations; }) return s.iterations;
  return 0;
}

// Returns the fixed-point passes of all steps.
[[gnu::noinline]] int run_steps() {
  int passes = 0;
  count_mark();
  for (int segment = 0; segment < check::kSegments; ++segment) {
    exported::reset(state);
    exported::set_applied_input(state, applied[segment]);
    check::resume_carried(state, segment);  // the SDRE's P; nothing for θ–D and the LQR
    for (int i = check::kSegmentStart[segment]; i < check::kSegmentStart[segment + 1]; ++i) {
      if (exported::step(state, times[i], measured[i], references[i], input) != thetad_onboard::Status::ok) ++failures;
      passes += passes_of(state);
    }
  }
  count_mark();
  return passes;
}

}  // namespace

int main() {
  for (int i = 0; i < check::kSamples; ++i) {
    times[i] = Scalar(check::kTime[i]);
    for (int j = 0; j < kN; ++j) measured[i][j] = Scalar(check::kMeasured[i][j]);
    for (int j = 0; j < 3; ++j) {
      references[i].position[j] = Scalar(check::kReference[i][j]);
      references[i].integral[j] = Scalar(check::kReference[i][3 + j]);
      references[i].velocity[j] = Scalar(check::kReference[i][6 + j]);
      references[i].acceleration[j] = Scalar(check::kReference[i][9 + j]);
    }
  }
  for (int s = 0; s < check::kSegments; ++s)
    for (int k = 0; k < kM; ++k) applied[s][k] = Scalar(check::kAppliedBefore[s][k]);
  const int passes = run_steps();
  std::printf("steps %d passes %d failures %d\n", check::kSamples, passes, failures);
  return failures == 0 ? 0 : 1;
}
