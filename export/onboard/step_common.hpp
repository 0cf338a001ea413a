#pragma once

// What every exported step shares: the reference it tracks, the tracking vector V_track of
// Eq. (36) (docs/model.md §7) and the data checksum. Standard C++ only; `thetad export` copies this
// file into the header it writes.

#ifndef THETAD_ONBOARD_STEP_COMMON
#define THETAD_ONBOARD_STEP_COMMON

#include <bit>
#include <cstdint>
#include <type_traits>

namespace thetad_onboard {

// core/control_law.hpp's Reference: the commanded NED position, its integral by the controller's
// left-rectangle rule (docs/model.md §7), and its velocity and acceleration.
template <class T>
struct Reference {
  T position[3];
  T integral[3];
  T velocity[3];
  T acceleration[3];
};

// V_track (Eq. 36, core/helicopter/tracking.cpp): position and integral errors, the other states
// as measured, s = 1.
template <class T>
void tracking_vector(const T* measured, const Reference<T>& reference, T* v) {
  for (int i = 0; i < 3; ++i) v[i] = measured[i] - reference.position[i];
  for (int i = 3; i < 14; ++i) v[i] = measured[i];
  for (int i = 0; i < 3; ++i) v[14 + i] = measured[14 + i] - reference.integral[i];
  v[17] = T(1.0);
}

// FNV-1a over the bit patterns of `count` values, continuing from `hash`: the exported data's
// checksum in the scalar type it is stored in (the generator computes the expected values).
template <class T>
constexpr std::uint64_t fnv1a(const T* values, int count, std::uint64_t hash) {
  using Bits = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
  for (int i = 0; i < count; ++i) {
    const Bits bits = std::bit_cast<Bits>(values[i]);
    for (unsigned byte = 0; byte < sizeof(Bits); ++byte) {
      hash ^= static_cast<std::uint64_t>((bits >> (8 * byte)) & 0xffu);
      hash *= 0x100000001b3ull;
    }
  }
  return hash;
}
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_STEP_COMMON
