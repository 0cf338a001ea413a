#include "core/grid_bracket.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thetad {

GridBracket bracket(const std::vector<double>& grid, double value) {
  if (!(value > grid.front())) return {0, 0, 0.0};
  if (value >= grid.back()) return {grid.size() - 1, grid.size() - 1, 0.0};
  const std::size_t high = static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), value) - grid.begin());
  return {high - 1, high, (value - grid[high - 1]) / (grid[high] - grid[high - 1])};
}

GridBracket periodic_bracket(const std::vector<double>& grid, double angle) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (grid.size() == 1) return {0, 0, 0.0};
  double c = std::fmod(angle, kTwoPi);
  if (c < 0.0) c += kTwoPi;
  if (c >= grid.front() && c < grid.back()) return bracket(grid, c);
  const double span = grid.front() + kTwoPi - grid.back();
  const double past_last = c >= grid.back() ? c - grid.back() : c + kTwoPi - grid.back();
  return {grid.size() - 1, 0, past_last / span};
}

}  // namespace thetad
