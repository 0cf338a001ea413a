#pragma once

#include <algorithm>
#include <cstddef>

namespace thetad {

// A string literal as a template argument (a controller's name in its class, a table row's name in
// the template that makes the row).
template <std::size_t N>
struct FixedString {
  // Implicit, so that a template takes the literal itself: NamedController<"name">.
  constexpr FixedString(const char (&text)[N]) { std::copy_n(text, N, value); }
  char value[N];
};

}  // namespace thetad
