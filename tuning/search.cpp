#include "tuning/search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include <nlopt.hpp>

#include "core/error.hpp"

namespace thetad::tuning {

namespace {

using Clock = std::chrono::steady_clock;

struct Algorithm {
  std::string name;
  nlopt::algorithm id;
  bool global;
};

const std::vector<Algorithm>& algorithms() {
  static const std::vector<Algorithm> list = {
      {"LN_BOBYQA", nlopt::LN_BOBYQA, false},         {"LN_COBYLA", nlopt::LN_COBYLA, false},
      {"LN_SBPLX", nlopt::LN_SBPLX, false},           {"LN_NELDERMEAD", nlopt::LN_NELDERMEAD, false},
      {"GN_DIRECT_L", nlopt::GN_DIRECT_L, true},      {"GN_ISRES", nlopt::GN_ISRES, true},
  };
  return list;
}

const Algorithm& find_algorithm(const std::string& name) {
  for (const Algorithm& a : algorithms())
    if (a.name == name) return a;
  std::string known;
  for (const Algorithm& a : algorithms()) known += (known.empty() ? "" : ", ") + a.name;
  throw Error("tuning: unknown algorithm '" + name + "' (known: " + known + ")");
}

std::string stop_text(nlopt::result result) {
  switch (result) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "stopval reached";
    case nlopt::FTOL_REACHED: return "ftol reached";
    case nlopt::XTOL_REACHED: return "xtol reached";
    case nlopt::MAXEVAL_REACHED: return "maxeval reached";
    case nlopt::MAXTIME_REACHED: return "maxtime reached";
    case nlopt::ROUNDOFF_LIMITED: return "roundoff limited";
    default: return "nlopt result " + std::to_string(static_cast<int>(result));
  }
}

Eigen::VectorXd start_or_ones(const Eigen::VectorXd& start, int parameters) {
  return start.size() == 0 ? Eigen::VectorXd::Ones(parameters) : start;
}

// The objective NLopt sees; keeps the best point itself, so that a search NLopt ends with an
// exception (round-off) still returns what it found.
struct Tracked {
  Tracked(const PointObjective& f, const FitOptions& o) : objective(f), options(o) {}

  const PointObjective& objective;
  const FitOptions& options;
  int evaluations = 0;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x;

  double operator()(const std::vector<double>& x) {
    // COBYLA's linear model, fitted through the huge value of a diverged draw, can step to NaN;
    // nothing flies there (a controller refuses NaN settings), and the huge value steers it back.
    const bool finite = std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
    const double value = finite ? objective(Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())))
                                : std::numeric_limits<double>::quiet_NaN();
    ++evaluations;
    const double ranked = std::isfinite(value) ? value : std::numeric_limits<double>::infinity();
    if (ranked < best || best_x.empty()) {
      best = ranked;
      best_x = x;
    }
    if (options.progress) options.progress(evaluations, best);
    // NaN would stall every NLopt algorithm; a huge value steers it away instead.
    return std::isfinite(value) ? value : std::numeric_limits<double>::max();
  }

  // NLopt's C++ wrapper turns whatever the objective throws into "nlopt failure": the exception
  // is kept here instead and rethrown once NLopt has stopped (a flight's error, a Ctrl-C from Python).
  std::exception_ptr failure;

  static double call(const std::vector<double>& x, std::vector<double>&, void* self) {
    Tracked& tracked = *static_cast<Tracked*>(self);
    try {
      return tracked(x);
    } catch (...) {
      tracked.failure = std::current_exception();
      throw nlopt::forced_stop();
    }
  }
};

std::string run_stage(Tracked& objective, nlopt::algorithm id, const std::vector<double>& lower,
                      const std::vector<double>& upper, std::vector<double> x, int max_evaluations,
                      const FitOptions& options, Clock::time_point deadline) {
  if (options.max_seconds > 0.0 && Clock::now() >= deadline) return stop_text(nlopt::MAXTIME_REACHED);
  nlopt::opt opt(id, static_cast<unsigned>(x.size()));
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(&Tracked::call, &objective);
  opt.set_xtol_rel(options.x_tolerance);
  opt.set_maxeval(max_evaluations);
  if (options.max_seconds > 0.0) opt.set_maxtime(std::chrono::duration<double>(deadline - Clock::now()).count());
  double value = 0.0;
  try {
    return stop_text(opt.optimize(x, value));
  } catch (const nlopt::roundoff_limited&) {
    return stop_text(nlopt::ROUNDOFF_LIMITED);
  } catch (const nlopt::forced_stop&) {
    std::rethrow_exception(objective.failure);  // only Tracked::call forces a stop, keeping what it caught
  } catch (const std::exception& error) {
    throw Error("tuning: NLopt " + std::string(opt.get_algorithm_name()) + " failed: " + error.what());
  }
}

}  // namespace

const std::vector<std::string>& fit_algorithms() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Algorithm& a : algorithms()) list.push_back(a.name);
    return list;
  }();
  return names;
}

void check_search_options(const FitOptions& o) {
  find_algorithm(o.algorithm);
  if (o.max_local_evaluations < 1 || o.max_global_evaluations < 1)
    throw Error("tuning: the evaluation limits must be >= 1");
  if (!(o.max_seconds >= 0.0) || !std::isfinite(o.max_seconds))
    throw Error("tuning: the time budget must be a finite number of seconds >= 0 (0: none)");
}

void check_fit_options(const FitOptions& o, int parameters) {
  check_search_options(o);
  if (parameters < 1) throw Error("tuning: nothing to tune: the theta-d series needs terms >= 2 to have a k_i, l_i");
  const auto check_box = [](const char* name, double lower, double upper) {
    if (!std::isfinite(lower) || !std::isfinite(upper))
      throw Error(std::string("tuning: the bounds of ") + name + " must be finite");
    if (!(lower <= upper))
      throw Error(std::string("tuning: the bounds of ") + name + " are reversed: lower " + std::to_string(lower) +
                  " > upper " + std::to_string(upper));
  };
  check_box("k", o.k_lower, o.k_upper);
  check_box("l", o.l_lower, o.l_upper);
  if (o.l_lower < 0.0) throw Error("tuning: l_i must stay >= 0 (e_i must settle to 1, Eq. 25)");
  const auto check_start = [parameters](const char* name, const Eigen::VectorXd& given, double lower, double upper) {
    const Eigen::VectorXd start = start_or_ones(given, parameters);
    if (start.size() != parameters)
      throw Error(std::string("tuning: the start ") + name + " needs " + std::to_string(parameters) + " entries");
    if ((start.array() < lower).any() || (start.array() > upper).any() || !start.allFinite())
      throw Error(std::string("tuning: the start ") + name + " lies outside its bounds");
  };
  check_start("k", o.k_start, o.k_lower, o.k_upper);
  check_start("l", o.l_start, o.l_lower, o.l_upper);
}

FitResult search_box(const PointObjective& objective, const SearchBox& box, const FitOptions& options) {
  check_search_options(options);
  const Eigen::Index size = box.start.size();
  if (size < 1 || box.lower.size() != size || box.upper.size() != size)
    throw Error("tuning: the search box has " + std::to_string(box.lower.size()) + " lower bounds, " +
                std::to_string(box.upper.size()) + " upper and " + std::to_string(size) + " start values");
  if (!box.lower.allFinite() || !box.upper.allFinite() || (box.lower.array() > box.upper.array()).any())
    throw Error("tuning: the search box's bounds must be finite and ordered");
  if (!box.start.allFinite() || (box.start.array() < box.lower.array()).any() ||
      (box.start.array() > box.upper.array()).any())
    throw Error("tuning: the search's start lies outside its box");
  const Algorithm& algorithm = find_algorithm(options.algorithm);
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.max_seconds));
  const auto values = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  const std::vector<double> lower = values(box.lower), upper = values(box.upper);

  Tracked tracked(objective, options);
  FitResult result;
  result.start_residual = tracked(values(box.start));
  if (algorithm.global) {
    nlopt::srand(options.seed);
    run_stage(tracked, algorithm.id, lower, upper, values(box.start), options.max_global_evaluations, options, deadline);
  }
  // Local polish (or the whole search): from the best point so far. The start point counts
  // against the budget: max_local_evaluations bounds the evaluations of a local search in all.
  result.stop_reason = run_stage(tracked, algorithm.global ? nlopt::LN_BOBYQA : algorithm.id, lower, upper,
                                 tracked.best_x, std::max(1, options.max_local_evaluations - (algorithm.global ? 0 : 1)),
                                 options, deadline);
  result.x = Eigen::Map<const Eigen::VectorXd>(tracked.best_x.data(), size);
  result.residual = tracked.best;
  result.evaluations = tracked.evaluations;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

SearchBox series_box(const FitOptions& options, int p) {
  check_fit_options(options, p);
  SearchBox box{Eigen::VectorXd(2 * p), Eigen::VectorXd(2 * p), Eigen::VectorXd(2 * p)};
  box.lower << Eigen::VectorXd::Constant(p, options.k_lower), Eigen::VectorXd::Constant(p, options.l_lower);
  box.upper << Eigen::VectorXd::Constant(p, options.k_upper), Eigen::VectorXd::Constant(p, options.l_upper);
  box.start << start_or_ones(options.k_start, p), start_or_ones(options.l_start, p);
  return box;
}

FitResult fit(const ParameterObjective& objective, int p, const FitOptions& options) {
  const SearchBox box = series_box(options, p);
  FitResult result = search_box([&](const Eigen::VectorXd& x) { return objective(x.head(p), x.tail(p)); }, box, options);
  result.k = result.x.head(p);
  result.l = result.x.tail(p);
  return result;
}

}  // namespace thetad::tuning
