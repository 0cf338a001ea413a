#pragma once

// The NLopt search shared by every tuning objective: a point x in a box, derivative-free, with an
// evaluation and a time budget. For θ–D's series x = (k_1 … k_{N−1}, l_1 … l_{N−1}); for a
// controller's weights the log10 factors of parameterization.hpp.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace thetad::tuning {

// The value a tuning objective gives to (k, l); smaller is better.
using ParameterObjective = std::function<double(const Eigen::VectorXd& k, const Eigen::VectorXd& l)>;
// The value a tuning objective gives to a point of its box; smaller is better.
using PointObjective = std::function<double(const Eigen::VectorXd& x)>;

// A box of parameters and the point a search starts from.
struct SearchBox {
  Eigen::VectorXd lower, upper, start;
};

struct FitOptions {
  // "LN_BOBYQA" (default), "LN_COBYLA", "LN_SBPLX", "LN_NELDERMEAD": local from the start point;
  // "GN_DIRECT_L", "GN_ISRES": global over the box first, then LN_BOBYQA from its best point.
  std::string algorithm = "LN_BOBYQA";
  // Box of docs/model.md §8.1 (docs/tuning.md gives the reasons): k_i ∈ [0, 1.5], l_i ∈ [0.01, 20].
  double k_lower = 0.0, k_upper = 1.5, l_lower = 0.01, l_upper = 20.0;
  // Start point; empty: the paper's k = l = 1 (docs/model.md §8.1).
  Eigen::VectorXd k_start, l_start;
  int max_local_evaluations = 1500;
  int max_global_evaluations = 800;
  double max_seconds = 0.0;   // wall-time budget of the whole search; 0: none
  double x_tolerance = 1e-9;  // relative, on k and l
  std::uint64_t seed = 1;     // GN_ISRES is randomized: NLopt's generator is seeded with this
  // Called after every evaluation with the count so far and the best value so far.
  std::function<void(int evaluations, double best)> progress;
};

// The algorithms FitOptions::algorithm accepts.
const std::vector<std::string>& fit_algorithms();
// Throws thetad::Error on an unknown algorithm, non-positive evaluation limits or a negative time budget.
void check_search_options(const FitOptions& options);
// check_search_options and, for the series: reversed or non-finite bounds of k or l, l_lower < 0, a
// start point of the wrong size or outside the box.
void check_fit_options(const FitOptions& options, int parameters);

struct FitResult {
  Eigen::VectorXd x;     // the best point of the box
  Eigen::VectorXd k, l;  // for the series: x split

  double start_residual = 0.0;  // the objective at the start point
  double residual = 0.0;        // at (k, l)
  int evaluations = 0;
  double seconds = 0.0;         // wall time of the search (what the objective precomputed is not included)
  std::string stop_reason;      // NLopt's, of the last stage
};

// Minimises `objective` over `box` with the algorithm, budgets, seed and progress of `options` (its
// k, l fields aside). A non-finite value (a diverged flight) counts as the largest double: NLopt
// then steers away from that point. Throws thetad::Error for a box whose sizes differ, that is not
// finite or ordered, or whose start lies outside it.
FitResult search_box(const PointObjective& objective, const SearchBox& box, const FitOptions& options);

// The box of `parameters` pairs (k_i, l_i), k first, from the bounds and start of `options`
// (checked by check_fit_options).
SearchBox series_box(const FitOptions& options, int parameters);

// search_box over `parameters` pairs (k_i, l_i) in series_box.
FitResult fit(const ParameterObjective& objective, int parameters, const FitOptions& options);

}  // namespace thetad::tuning
