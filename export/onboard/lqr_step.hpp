#pragma once

// The hover LQR's step (controllers/lqr.cpp): u = u* − K (V − V*) on the design states, V the
// tracking vector. Design is the generated constants: input (u*), tracking (V*), gain (K,
// row-major m × design_states). Standard C++ only; `thetad export` copies this file into the
// header it writes.

#ifndef THETAD_ONBOARD_LQR_STEP
#define THETAD_ONBOARD_LQR_STEP

namespace thetad_onboard {

// The LQR keeps nothing between steps; the struct is there so that every exported step has the
// same calling convention.
template <class T>
struct LqrState {
  T time;
};

template <class T, class Design>
void lqr_reset(LqrState<T>& state) {
  state.time = T(Design::start_time);
}

template <class T, class Design>
Status lqr_step(LqrState<T>& state, T t, const T* measured, const Reference<T>& reference, T* u) {
  constexpr int design_states = Design::design_states;
  T v[kStates];
  tracking_vector(measured, reference, v);
  for (int i = 0; i < design_states; ++i) v[i] -= Design::tracking[i];
  for (int k = 0; k < kInputs; ++k) {
    T sum = T(0);
    for (int i = 0; i < design_states; ++i) sum += Design::gain[k * design_states + i] * v[i];
    u[k] = Design::input[k] - sum;
    if (!std::isfinite(u[k])) return Status::not_finite;
  }
  state.time = t;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_LQR_STEP
