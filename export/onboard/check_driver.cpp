// The exported controller's check (docs/onboard.md): the recorded samples of a library flight fed
// in order to the exported step, in double (equal to the library's u to a relative R-norm tolerance,
// 1e-12 unless argv[1] says otherwise) and in float (its differences reported: median, p99, max;
// held to argv[2] when given). No heap: operator new and delete abort, and so does malloc while a
// step runs (glibc). Exits 0 when the double step passes, the float step (with argv[2]) too, and
// the data checksums hold; 1 otherwise. `thetad export` writes it
// after the lines that name the exported header and its check data (namespaces `exported`, `check`).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>

namespace {

bool allocation_forbidden = false;

[[noreturn]] void allocation_called(const char* what) {
  std::fprintf(stderr, "check: %s called: the exported step must not allocate\n", what);
  std::abort();
}

}  // namespace

void* operator new(std::size_t) { allocation_called("operator new"); }
void* operator new[](std::size_t) { allocation_called("operator new[]"); }
void* operator new(std::size_t, std::align_val_t) { allocation_called("operator new"); }
void* operator new[](std::size_t, std::align_val_t) { allocation_called("operator new[]"); }
void* operator new(std::size_t, const std::nothrow_t&) noexcept { allocation_called("operator new"); }
void* operator new[](std::size_t, const std::nothrow_t&) noexcept { allocation_called("operator new[]"); }
void operator delete(void*) noexcept { allocation_called("operator delete"); }
void operator delete[](void*) noexcept { allocation_called("operator delete[]"); }
void operator delete(void*, std::size_t) noexcept { allocation_called("operator delete"); }
void operator delete[](void*, std::size_t) noexcept { allocation_called("operator delete[]"); }
void operator delete(void*, std::align_val_t) noexcept { allocation_called("operator delete"); }
void operator delete[](void*, std::align_val_t) noexcept { allocation_called("operator delete[]"); }

#if defined(__GLIBC__)
// The C library's own allocator stays for stdio outside the steps.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t size) noexcept {
  if (allocation_forbidden) allocation_called("malloc");
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  if (allocation_forbidden) allocation_called("calloc");
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  if (allocation_forbidden) allocation_called("realloc");
  return __libc_realloc(pointer, size);
}
void free(void* pointer) noexcept {
  if (allocation_forbidden && pointer) allocation_called("free");
  __libc_free(pointer);
}
}
#endif

namespace {

constexpr int kN = thetad_onboard::kStates, kM = thetad_onboard::kInputs;

// ‖R^{1/2} d‖ = sqrt(dᵀ R d).
double r_norm(const double* d) {
  double sum = 0.0;
  for (int i = 0; i < kM; ++i)
    for (int j = 0; j < kM; ++j) sum += d[i] * exported::kInputWeights[i * kM + j] * d[j];
  return std::sqrt(sum);
}

// The exported step in T along every recorded segment; the relative R-norm differences from the
// library's u into `errors`. Returns the first status that is not ok (and where), else ok.
template <class T>
thetad_onboard::Status run(double* errors, int& failed_at) {
  static exported::State<T> state;  // static: its buffers are not the stack's
  for (int segment = 0; segment < check::kSegments; ++segment) {
    exported::reset(state);
    T applied[kM];
    for (int k = 0; k < kM; ++k) applied[k] = T(check::kAppliedBefore[segment][k]);
    exported::set_applied_input(state, applied);
    check::resume_carried(state, segment);
    for (int i = check::kSegmentStart[segment]; i < check::kSegmentStart[segment + 1]; ++i) {
      T measured[kN], u[kM];
      for (int j = 0; j < kN; ++j) measured[j] = T(check::kMeasured[i][j]);
      thetad_onboard::Reference<T> reference;
      for (int j = 0; j < 3; ++j) {
        reference.position[j] = T(check::kReference[i][j]);
        reference.integral[j] = T(check::kReference[i][3 + j]);
        reference.velocity[j] = T(check::kReference[i][6 + j]);
        reference.acceleration[j] = T(check::kReference[i][9 + j]);
      }
      allocation_forbidden = true;
      const thetad_onboard::Status status = exported::step(state, T(check::kTime[i]), measured, reference, u);
      allocation_forbidden = false;
      if (status != thetad_onboard::Status::ok) {
        failed_at = i;
        return status;
      }
      double difference[kM];
      for (int k = 0; k < kM; ++k) difference[k] = double(u[k]) - check::kInput[i][k];
      errors[i] = r_norm(difference) / r_norm(check::kInput[i]);
    }
  }
  return thetad_onboard::Status::ok;
}

double errors_double[check::kSamples], errors_float[check::kSamples];

// The q-quantile of `sorted` by nearest rank.
double quantile(const double* sorted, double q) {
  const int rank = static_cast<int>(std::ceil(q * check::kSamples));
  return sorted[rank < 1 ? 0 : rank - 1];
}

}  // namespace

int main(int argc, char** argv) {
  const double tolerance = argc > 1 ? std::atof(argv[1]) : 1e-12;
  const double float_tolerance = argc > 2 ? std::atof(argv[2]) : -1.0;  // negative: report only
  std::printf("%s (%s): %d recorded samples in %d segments\n", exported::kLabel, exported::kController,
              check::kSamples, check::kSegments);
  const bool intact = exported::data_intact<double>() && exported::data_intact<float>();
  std::printf("data checksums (double, float): %s\n", intact ? "ok" : "MISMATCH");
  int failed_at = -1;
  thetad_onboard::Status status = run<double>(errors_double, failed_at);
  if (status != thetad_onboard::Status::ok) {
    std::printf("double step failed at sample %d: %s\n", failed_at, thetad_onboard::status_name(status));
    return 1;
  }
  const double worst = *std::max_element(errors_double, errors_double + check::kSamples);
  std::printf("double: largest relative R-norm difference from the library %.3g (tolerance %.3g): %s\n", worst,
              tolerance, worst <= tolerance ? "pass" : "FAIL");
  bool float_passed = float_tolerance < 0.0;
  status = run<float>(errors_float, failed_at);
  if (status != thetad_onboard::Status::ok) {
    std::printf("float step failed at sample %d: %s\n", failed_at, thetad_onboard::status_name(status));
  } else {
    std::sort(errors_float, errors_float + check::kSamples);
    const double worst_float = errors_float[check::kSamples - 1];
    std::printf("float: relative R-norm difference from the library: median %.3g, p99 %.3g, max %.3g", quantile(errors_float, 0.5),
                quantile(errors_float, 0.99), worst_float);
    if (float_tolerance >= 0.0) {
      float_passed = worst_float <= float_tolerance;
      std::printf(" (tolerance %.3g): %s", float_tolerance, float_passed ? "pass" : "FAIL");
    }
    std::printf("\n");
  }
  return intact && worst <= tolerance && float_passed ? 0 : 1;
}
