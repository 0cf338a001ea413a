#pragma once

#include <cstddef>
#include <vector>

namespace thetad {

// Where a value falls on a grid axis for multilinear blending:
// value ≈ (1 − weight) · grid[low] + weight · grid[high].
struct GridBracket {
  std::size_t low = 0, high = 0;
  double weight = 0.0;
};

// On an ascending axis, clamped at the ends (no extrapolation beyond the grid); NaN gives the first point.
GridBracket bracket(const std::vector<double>& grid, double value);
// On an ascending axis of angles in [0, 2π) that wraps: between the last and the first + 2π.
GridBracket periodic_bracket(const std::vector<double>& grid, double angle);

// The corners of the trilinear blend of three axes' brackets, as visit(low-or-high index on each
// axis, weight), the weights summing to 1; corners of zero weight are skipped.
template <class Visit>
void for_each_corner(const GridBracket& a, const GridBracket& b, const GridBracket& c, Visit&& visit) {
  for (int corner = 0; corner < 8; ++corner) {
    const bool high_a = corner & 1, high_b = corner & 2, high_c = corner & 4;
    const double weight = (high_a ? a.weight : 1.0 - a.weight) * (high_b ? b.weight : 1.0 - b.weight) *
                          (high_c ? c.weight : 1.0 - c.weight);
    if (weight == 0.0) continue;
    visit(high_a ? a.high : a.low, high_b ? b.high : b.low, high_c ? c.high : c.low, weight);
  }
}

}  // namespace thetad
