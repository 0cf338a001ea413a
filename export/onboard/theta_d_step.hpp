#pragma once

// The θ–D step (docs/model.md §7, §8.1; controllers/theta_d_step.cpp) at a design done offline:
// u = −R⁻¹ Bᵀ(x) Σ_{i<N} T_i(x, t) V with T0 the CARE solution at the initial state and T_i, i ≥ 1,
// from T_i Ac0 + Ac0ᵀ T_i = e_i(t) W_i by the precomputed inverse of that Lyapunov operator on the
// n(n+1)/2 unknowns; the fixed point u → F(x; u), B(x; u) → u' of docs/model.md §6.2 around it.
// Design is the generated constants (see export/theta_d_export.cpp for their meaning). Standard
// C++ only; `thetad export` copies this file into the header it writes.

#ifndef THETAD_ONBOARD_THETA_D_STEP
#define THETAD_ONBOARD_THETA_D_STEP

#include <cmath>

namespace thetad_onboard {

inline constexpr int kUnknowns = kStates * (kStates + 1) / 2;

// Everything a θ–D step keeps between samples (the input it applied: the fixed point starts there)
// and its buffers, so that a step allocates nothing and needs little stack.
template <class T, int Terms>
struct ThetaDState {
  T time;
  T applied[kInputs];
  int iterations;    // fixed-point passes of the last step
  T input_change;    // max|Δu| of its last pass
  // Buffers of one pass.
  T v[kStates], t0_v[kStates], gradient[kStates];
  T F[kStates * kStates], B[kStates * kInputs];
  T g_tilde_scaled[kStates * kInputs];         // (B − g0) L⁻ᵀ, on the input rows
  T term[Terms][kStates * kStates];            // T_i, i < N − 1 (T_0 is a design constant)
  T y[Terms][kStates * kInputs], z[Terms][kStates * kInputs], pair[Terms][kStates * kInputs];
  T m[kStates * kStates];                      // W_i = M + Mᵀ
  T packed_right[kUnknowns], packed_term[kUnknowns];
  int a_tilde_count;
  int a_tilde_row[kStates * kStates], a_tilde_col[kStates * kStates];
  T a_tilde_value[kStates * kStates];
  T reference_state[kStates], reference_rate[kStates];  // feed-forward velocity: x_r and ẋ_r
};

template <class T, class Design>
void theta_d_reset(ThetaDState<T, Design::terms>& state) {
  state.time = Design::start_time;
  for (int k = 0; k < kInputs; ++k) state.applied[k] = Design::initial_input[k];
  state.iterations = 0;
  state.input_change = T(0);
}

namespace detail {

// out (n × m) = left (n × n, row-major) · right (n × m) on the input rows only (the other
// rows of right are zero).
template <class T>
void product_on_input_rows(const T* left, const T* right, T* out) {
  for (int r = 0; r < kStates; ++r)
    for (int k = 0; k < kInputs; ++k) {
      T sum = T(0);
      for (int a = 0; a < kInputRowCount; ++a) sum += left[r * kStates + kInputRows[a]] * right[kInputRows[a] * kInputs + k];
      out[r * kInputs + k] = sum;
    }
}

// m += weight · a bᵀ for n × m factors.
template <class T>
void add_outer(T weight, const T* a, const T* b, T* m) {
  for (int r = 0; r < kStates; ++r)
    for (int c = 0; c < kStates; ++c) {
      T sum = T(0);
      for (int k = 0; k < kInputs; ++k) sum += a[r * kInputs + k] * b[c * kInputs + k];
      m[r * kStates + c] += weight * sum;
    }
}

// The feed-forward velocity error form (core/error_form_plant.cpp, docs/model.md §7.1): the
// commanded motion x_r, ẋ_r (Helicopter::commanded_motion, the design point zero).
template <class T, class Design>
Status aim(ThetaDState<T, Design::terms>& s, const HelicopterConstants& p, const T* measured,
           const Reference<T>& reference) {
  AirData<T> air;
  const Status status = air_data(p, measured, air);
  if (status != Status::ok) return status;
  for (int i = 0; i < kStates; ++i) s.reference_state[i] = s.reference_rate[i] = T(0);
  T body_velocity[3], body_acceleration[3];
  for (int c = 0; c < 3; ++c) {
    body_velocity[c] = body_acceleration[c] = T(0);
    for (int r = 0; r < 3; ++r) {
      body_velocity[c] += air.rotation[r * 3 + c] * reference.velocity[r];
      body_acceleration[c] += air.rotation[r * 3 + c] * reference.acceleration[r];
    }
  }
  const T* rates = measured + kP;
  const T cross[3] = {rates[1] * body_velocity[2] - rates[2] * body_velocity[1],
                      rates[2] * body_velocity[0] - rates[0] * body_velocity[2],
                      rates[0] * body_velocity[1] - rates[1] * body_velocity[0]};
  for (int i = 0; i < 3; ++i) {
    s.reference_state[kXp + i] = reference.position[i];
    s.reference_state[kU + i] = body_velocity[i];
    s.reference_state[kXi + i] = reference.integral[i];
    s.reference_rate[kXp + i] = reference.velocity[i];
    s.reference_rate[kU + i] = body_acceleration[i] - cross[i];
    s.reference_rate[kXi + i] = reference.position[i];
  }
  return Status::ok;
}

// One pass of the series at (x; guess): `update` = −R⁻¹ Bᵀ Σ T_i v.
template <class T, class Design>
Status theta_d_pass(ThetaDState<T, Design::terms>& s, const HelicopterConstants& p, T elapsed, const T* x,
                    const T* guess, T* update) {
  constexpr int terms = Design::terms;
  // The decision variable is v = u − u_r with u_r = 0 (the design point of θ–D's error form), so
  // the plant sees the guess itself.
  const Status status = helicopter_sdc(p, x, guess[kTmr], s.F, s.B);
  if (status != Status::ok) return status;
  if (Design::feedforward_velocity) {
    // F's bias column += F x_r + B u_r − ẋ_r (u_r = 0).
    T terms_column[kStates];
    for (int r = 0; r < kStates; ++r) {
      T sum = T(0);
      for (int c = 0; c < kStates; ++c) sum += s.F[r * kStates + c] * s.reference_state[c];
      terms_column[r] = sum - s.reference_rate[r];
    }
    for (int r = 0; r < kStates; ++r) s.F[r * kStates + kS] += terms_column[r];
  }
  for (int r = 0; r < kStates; ++r) s.gradient[r] = s.t0_v[r];
  if (terms > 1) {
    // Ã = F − A0, its nonzeros column by column; g̃ L⁻ᵀ on the input rows.
    s.a_tilde_count = 0;
    for (int c = 0; c < kStates; ++c)
      for (int r = 0; r < kStates; ++r) {
        const T value = s.F[r * kStates + c] - Design::a0[r * kStates + c];
        if (value == T(0)) continue;
        s.a_tilde_row[s.a_tilde_count] = r;
        s.a_tilde_col[s.a_tilde_count] = c;
        s.a_tilde_value[s.a_tilde_count++] = value;
      }
    for (int r = 0; r < kStates * kInputs; ++r) s.g_tilde_scaled[r] = T(0);
    for (int a = 0; a < kInputRowCount; ++a) {
      const int r = kInputRows[a];
      for (int k = 0; k < kInputs; ++k) {
        T sum = T(0);
        for (int l = 0; l < kInputs; ++l) sum += s.B[r * kInputs + l] * Design::r_inverse_sqrt_t[l * kInputs + k];
        s.g_tilde_scaled[r * kInputs + k] = sum - Design::g0_scaled[r * kInputs + k];
      }
    }
    product_on_input_rows(Design::t0, s.g_tilde_scaled, s.z[0]);  // Z0
  }
  for (int i = 1; i < terms; ++i) {
    // W_i = M + Mᵀ, M = −T_{i−1} Ã + Y0 Z_{i−1}ᵀ + Σ_{1≤j<i−j} C_j C_{i−j}ᵀ + ½ C_{i/2} C_{i/2}ᵀ
    // (i even), C_j = Y_j + Z_{j−1}: theta_d_step.cpp's form_right_side.
    const T* previous = i == 1 ? Design::t0 : s.term[i - 1];
    for (int e = 0; e < kStates * kStates; ++e) s.m[e] = T(0);
    for (int e = 0; e < s.a_tilde_count; ++e) {
      const int r = s.a_tilde_row[e], c = s.a_tilde_col[e];
      for (int row = 0; row < kStates; ++row) s.m[row * kStates + c] -= s.a_tilde_value[e] * previous[row * kStates + r];
    }
    add_outer(T(1.0), Design::y0, s.z[i - 1], s.m);
    for (int j = 1; j < i - j; ++j) add_outer(T(1.0), s.pair[j], s.pair[i - j], s.m);
    if (i % 2 == 0) add_outer(T(0.5), s.pair[i / 2], s.pair[i / 2], s.m);
    for (int a = 0; a < kUnknowns; ++a) {
      const int r = Design::unknown_row[a], c = Design::unknown_col[a];
      s.packed_right[a] = s.m[r * kStates + c] + s.m[c * kStates + r];
    }
    // Eqs. (24)-(25): T_i = e_i(t) L⁻¹ W_i; the last term only where Bᵀ reads it.
    const T factor = T(1.0) - Design::k[i - 1] * std::exp(-Design::l[i - 1] * elapsed);
    const bool last = i + 1 == terms;
    const int solved = last ? Design::input_row_unknowns : kUnknowns;
    for (int a = 0; a < solved; ++a) {
      T sum = T(0);
      const T* row = Design::lyapunov_inverse + a * kUnknowns;
      for (int b = 0; b < kUnknowns; ++b) sum += row[b] * s.packed_right[b];
      s.packed_term[a] = factor * sum;
    }
    if (last) {
      // The rows outside the input rows get partial sums; Bᵀ reads none of them.
      for (int a = 0; a < solved; ++a) {
        const int r = Design::unknown_row[a], c = Design::unknown_col[a];
        s.gradient[r] += s.packed_term[a] * s.v[c];
        if (r != c) s.gradient[c] += s.packed_term[a] * s.v[r];
      }
      break;
    }
    T* term = s.term[i];
    for (int a = 0; a < kUnknowns; ++a) {
      const int r = Design::unknown_row[a], c = Design::unknown_col[a];
      term[r * kStates + c] = term[c * kStates + r] = s.packed_term[a];
    }
    for (int r = 0; r < kStates; ++r) {
      T sum = T(0);
      for (int c = 0; c < kStates; ++c) sum += term[r * kStates + c] * s.v[c];
      s.gradient[r] += sum;
    }
    product_on_input_rows(term, Design::g0_scaled, s.y[i]);
    product_on_input_rows(term, s.g_tilde_scaled, s.z[i]);
    for (int e = 0; e < kStates * kInputs; ++e) s.pair[i][e] = s.y[i][e] + s.z[i - 1][e];
  }
  // Eq. (35): u = −R⁻¹ Bᵀ (Σ T_i) V.
  T bt_gradient[kInputs];
  for (int k = 0; k < kInputs; ++k) {
    T sum = T(0);
    for (int a = 0; a < kInputRowCount; ++a) sum += s.B[kInputRows[a] * kInputs + k] * s.gradient[kInputRows[a]];
    bt_gradient[k] = sum;
  }
  for (int k = 0; k < kInputs; ++k) {
    T sum = T(0);
    for (int l = 0; l < kInputs; ++l) sum += Design::r_inverse[k * kInputs + l] * bt_gradient[l];
    update[k] = -sum;
  }
  return Status::ok;
}

}  // namespace detail

// One control step at time t on the measured 18-state (its integral entries the integral of the
// measured position, s = 1) for `reference`: writes u (5) and returns Status::ok, or a status and
// leaves u and the state's applied input as they were.
template <class T, class Design>
Status theta_d_step(ThetaDState<T, Design::terms>& s, const HelicopterConstants& p, T t, const T* measured,
                    const Reference<T>& reference, T* u) {
  if (Design::feedforward_velocity) {
    const Status status = detail::aim<T, Design>(s, p, measured, reference);
    if (status != Status::ok) return status;
    for (int i = 0; i < kStates; ++i) s.v[i] = measured[i] - s.reference_state[i];
    s.v[kS] = T(1.0);
  } else {
    tracking_vector(measured, reference, s.v);
  }
  for (int r = 0; r < kStates; ++r) {
    T sum = T(0);
    for (int c = 0; c < kStates; ++c) sum += Design::t0[r * kStates + c] * s.v[c];
    s.t0_v[r] = sum;
  }
  // One pass is exact when the SDC does not depend on the input (the governor model).
  const int passes = p.rotor_speed_governor ? 1 : Design::fixed_point_iterations;
  const T elapsed = t - Design::start_time;
  T guess[kInputs];
  const Status status = fixed_point(s.applied, passes, T(Design::fixed_point_tolerance), s.iterations, s.input_change,
                                    guess, [&](const T* input, T* update) {
                                      return detail::theta_d_pass<T, Design>(s, p, elapsed, measured, input, update);
                                    });
  if (status != Status::ok) return status;
  for (int k = 0; k < kInputs; ++k) s.applied[k] = u[k] = guess[k];
  s.time = t;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_THETA_D_STEP
