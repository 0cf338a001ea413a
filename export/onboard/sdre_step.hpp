#pragma once

// The SDRE's capped step (controllers/sdre.hpp, mode capped; docs/model.md §8.2, Eq. 37): at every
// pass of the fixed point u → F(x; u), B(x; u) → u' (docs/model.md §6.2), exactly K Newton–Kleinman
// steps from the P the last pass or sample left (core/capped_newton_kleinman.hpp), each a Lyapunov
// solve of the closed loop (lyapunov_schur.hpp), then u = −R⁻¹ Bᵀ P v. There is no Riccati solver
// on board: reset() loads the P the library's cold solve found at the design point (the
// scenario's initial state with the initial input), from which the library's capped mode starts
// too. Design is the generated constants (export/sdre_export.cpp). Standard C++ only; `thetad
// export` copies this file into the header it writes.

#ifndef THETAD_ONBOARD_SDRE_STEP
#define THETAD_ONBOARD_SDRE_STEP

#include <cmath>

namespace thetad_onboard {

// What an SDRE step keeps between samples (P and the applied input) and its buffers.
template <class T>
struct SdreState {
  T time;
  T applied[kInputs];
  int iterations;  // fixed-point passes of the last step
  T input_change;  // max|Δu| of its last pass
  T value[kStates * kStates];    // P of the last sample
  T iterate[kStates * kStates];  // P of the step under way (committed when it succeeds)
  T v[kStates], pv[kStates];
  T F[kStates * kStates], B[kStates * kInputs];
  T w[kInputs * kStates], wp[kInputs * kStates];  // W = L⁻¹Bᵀ (R = LLᵀ) and W P
  T residual[kStates * kStates], closed_loop[kStates * kStates], delta[kStates * kStates];
  SchurWorkspace<T, kStates> schur;
};

template <class T, class Design>
void sdre_reset(SdreState<T>& state) {
  state.time = T(Design::start_time);
  for (int k = 0; k < kInputs; ++k) state.applied[k] = T(Design::initial_input[k]);
  for (int e = 0; e < kStates * kStates; ++e) state.value[e] = T(Design::p0[e]);
  state.iterations = 0;
  state.input_change = T(0);
}

namespace detail {

// One Newton–Kleinman step on s.iterate for (F, W): Res = FᵀP + PF − (WP)ᵀ(WP) + Q, then
// (F − WᵀWP)ᵀΔ + Δ(F − WᵀWP) + Res = 0 and P += Δ, symmetrized (care_weights.cpp's care_residual
// and symmetrize, in their order).
template <class T, class Design>
Status newton_kleinman_step(SdreState<T>& s) {
  constexpr int n = kStates, m = kInputs;
  for (int k = 0; k < m; ++k)
    for (int c = 0; c < n; ++c) {
      T sum = T(0);
      for (int r = 0; r < n; ++r) sum += s.w[k * n + r] * s.iterate[r * n + c];
      s.wp[k * n + c] = sum;
    }
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      T sum = T(0);
      for (int k = 0; k < n; ++k) sum += s.F[k * n + r] * s.iterate[k * n + c];
      s.residual[r * n + c] = sum;
    }
  for (int c = 0; c < n; ++c) {
    s.residual[c * n + c] *= T(2.0);
    for (int r = 0; r < c; ++r) s.residual[r * n + c] = s.residual[c * n + r] = s.residual[r * n + c] + s.residual[c * n + r];
  }
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      T sum = T(0), gain = T(0);
      for (int k = 0; k < m; ++k) {
        sum += s.wp[k * n + r] * s.wp[k * n + c];
        gain += s.w[k * n + r] * s.wp[k * n + c];
      }
      s.residual[r * n + c] = s.residual[r * n + c] - sum + T(Design::q[r * n + c]);
      s.closed_loop[r * n + c] = s.F[r * n + c] - gain;
    }
  Status status = real_schur(s.closed_loop, s.schur);
  if (status != Status::ok) return status;
  for (int i = 0; i < n; ++i)
    if (!(s.schur.wr[i] < T(0))) return Status::closed_loop_not_hurwitz;
  status = lyapunov_solve(s.schur, s.residual, s.delta);
  if (status != Status::ok) return status;
  for (int c = 0; c < n; ++c)
    for (int r = 0; r < n; ++r) s.iterate[r * n + c] += s.delta[r * n + c];
  for (int c = 0; c < n; ++c)
    for (int r = 0; r < c; ++r)
      s.iterate[r * n + c] = s.iterate[c * n + r] = T(0.5) * (s.iterate[r * n + c] + s.iterate[c * n + r]);
  return Status::ok;
}

// One pass at (x; guess): K Newton steps from s.iterate, then `update` = −R⁻¹ Bᵀ P v.
template <class T, class Design>
Status sdre_pass(SdreState<T>& s, const HelicopterConstants& p, const T* x, const T* guess, T* update) {
  constexpr int n = kStates, m = kInputs;
  Status status = helicopter_sdc(p, x, guess[kTmr], s.F, s.B);
  if (status != Status::ok) return status;
  // W = L⁻¹Bᵀ by forward substitution, column by column of Bᵀ (care_weights.cpp's set_input_matrix).
  for (int c = 0; c < n; ++c)
    for (int k = 0; k < m; ++k) {
      T sum = s.B[c * m + k];
      for (int l = 0; l < k; ++l) sum -= T(Design::r_cholesky[k * m + l]) * s.w[l * n + c];
      s.w[k * n + c] = sum / T(Design::r_cholesky[k * m + k]);
    }
  for (int step = 0; step < Design::newton_iterations; ++step) {
    status = newton_kleinman_step<T, Design>(s);
    if (status != Status::ok) return status;
  }
  for (int r = 0; r < n; ++r) {
    T sum = T(0);
    for (int c = 0; c < n; ++c) sum += s.iterate[r * n + c] * s.v[c];
    s.pv[r] = sum;
  }
  T bt_pv[m];
  for (int k = 0; k < m; ++k) {
    T sum = T(0);
    for (int r = 0; r < n; ++r) sum += s.B[r * m + k] * s.pv[r];
    bt_pv[k] = sum;
  }
  for (int k = 0; k < m; ++k) {
    T sum = T(0);
    for (int l = 0; l < m; ++l) sum += T(Design::r_inverse[k * m + l]) * bt_pv[l];
    update[k] = -sum;
  }
  return Status::ok;
}

}  // namespace detail

// One control step at time t on the measured 18-state (its integral entries the integral of the
// measured position, s = 1) for `reference`: writes u (5) and returns Status::ok, or a status and
// leaves u, P and the applied input as they were (the library would solve cold there).
template <class T, class Design>
Status sdre_step(SdreState<T>& s, const HelicopterConstants& p, T t, const T* measured, const Reference<T>& reference,
                 T* u) {
  tracking_vector(measured, reference, s.v);
  for (int e = 0; e < kStates * kStates; ++e) s.iterate[e] = s.value[e];
  // One pass is exact when the SDC does not depend on the input (the governor model).
  const int passes = p.rotor_speed_governor ? 1 : Design::fixed_point_iterations;
  T guess[kInputs];
  const Status status = fixed_point(s.applied, passes, T(Design::fixed_point_tolerance), s.iterations, s.input_change,
                                    guess, [&](const T* input, T* update) {
                                      return detail::sdre_pass<T, Design>(s, p, measured, input, update);
                                    });
  if (status != Status::ok) return status;
  for (int e = 0; e < kStates * kStates; ++e) s.value[e] = s.iterate[e];
  for (int k = 0; k < kInputs; ++k) s.applied[k] = u[k] = guess[k];
  s.time = t;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_SDRE_STEP
