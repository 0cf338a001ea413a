#include "tuning/sigma_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "core/error.hpp"
#include "tuning/parallel.hpp"

namespace thetad::tuning {

namespace {

// Samples per chunk of the parallel loops: small enough to balance two workers, large enough
// that the per-chunk overhead is nothing next to 128 eigenvalue problems.
constexpr std::size_t kChunk = 128;

struct Algorithm {
  std::string name;
  nlopt::algorithm id;
  bool global;
};

const std::vector<Algorithm>& algorithms() {
  static const std::vector<Algorithm> list = {
      {"LN_BOBYQA", nlopt::LN_BOBYQA, false},     {"LN_SBPLX", nlopt::LN_SBPLX, false},
      {"LN_NELDERMEAD", nlopt::LN_NELDERMEAD, false}, {"GN_DIRECT_L", nlopt::GN_DIRECT_L, true},
      {"GN_ISRES", nlopt::GN_ISRES, true},
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

// The objective NLopt sees: x = (k_1 … k_{N−1}, l_1 … l_{N−1}); keeps the best point itself, so
// that a search NLopt ends with an exception (round-off) still returns what it found.
struct Objective {
  Objective(const SigmaMatch& m, const FitOptions& o) : match(m), options(o) {}

  const SigmaMatch& match;
  const FitOptions& options;
  int evaluations = 0;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x;

  double operator()(const std::vector<double>& x) {
    const auto p = static_cast<Eigen::Index>(x.size() / 2);
    const Eigen::Map<const Eigen::VectorXd> k(x.data(), p), l(x.data() + p, p);
    const double value = match.residual(k, l, options.weighting);
    ++evaluations;
    if (value < best) {
      best = value;
      best_x = x;
    }
    if (options.progress) options.progress(evaluations, best);
    // NaN would stall every NLopt algorithm; a huge value steers it away instead.
    return std::isfinite(value) ? value : std::numeric_limits<double>::max();
  }

  static double call(const std::vector<double>& x, std::vector<double>&, void* self) {
    return (*static_cast<Objective*>(self))(x);
  }
};

std::string run_stage(Objective& objective, nlopt::algorithm id, const std::vector<double>& lower,
                      const std::vector<double>& upper, std::vector<double> x, int max_evaluations, double x_tolerance) {
  nlopt::opt opt(id, static_cast<unsigned>(x.size()));
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(&Objective::call, &objective);
  opt.set_xtol_rel(x_tolerance);
  opt.set_maxeval(max_evaluations);
  double value = 0.0;
  try {
    return stop_text(opt.optimize(x, value));
  } catch (const nlopt::roundoff_limited&) {
    return stop_text(nlopt::ROUNDOFF_LIMITED);
  } catch (const thetad::Error&) {
    throw;
  } catch (const std::exception& error) {
    throw Error("tuning: NLopt " + std::string(opt.get_algorithm_name()) + " failed: " + error.what());
  }
}

}  // namespace

double sigma_max_symmetric(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver, const Eigen::MatrixXd& P) {
  solver.compute(P, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw Error("tuning: the symmetric eigenvalue solver did not converge");
  // Eigenvalues come sorted: the extremes hold the largest magnitude.
  return std::max(std::abs(solver.eigenvalues()[0]), std::abs(solver.eigenvalues()[P.rows() - 1]));
}

SigmaMatch::SigmaMatch(const ThetaDController& controller, const TuningRecord& record, int threads)
    : terms_(controller.settings().terms), threads_(std::max(1, threads)), n_(controller.T0().rows()),
      sigma_sdre_(record.sigma_sdre) {
  const Eigen::Index m = controller.g0().cols();
  if (record.states.rows() != n_ || record.inputs.rows() != m)
    throw Error("tuning: the record has " + std::to_string(record.states.rows()) + " states and " +
                std::to_string(record.inputs.rows()) + " inputs, the controller's plant " + std::to_string(n_) +
                " and " + std::to_string(m));
  if (record.size() == 0) throw Error("tuning: the record has no samples");
  const auto K = static_cast<std::size_t>(record.size());
  for (double t : record.time) elapsed_.push_back(t - controller.start_time());

  std::vector<ThetaDController> copies(static_cast<std::size_t>(threads_), controller);
  powers_ = copies[0].series_expansion(record.states.col(0), record.inputs.col(0)).powers;
  const std::size_t pieces = powers_.size(), packed_size = static_cast<std::size_t>(n_ * (n_ + 1) / 2);
  packed_.resize(K * pieces * packed_size);
  for_each_chunk(K, kChunk, threads_, [&](int worker, std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const auto column = static_cast<Eigen::Index>(k);
      const SeriesExpansion expansion =
          copies[static_cast<std::size_t>(worker)].series_expansion(record.states.col(column), record.inputs.col(column));
      double* out = packed_.data() + k * pieces * packed_size;
      for (const Eigen::MatrixXd& piece : expansion.pieces)
        for (Eigen::Index c = 0; c < n_; ++c)
          for (Eigen::Index r = c; r < n_; ++r) *out++ = piece(r, c);
    }
  });
}

void SigmaMatch::for_each_sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                                const std::function<void(std::size_t, Eigen::Index, double)>& visit) const {
  if (k.size() != parameters() || l.size() != parameters())
    throw Error("tuning: k and l need " + std::to_string(parameters()) + " entries each");
  const std::size_t pieces = powers_.size(), packed_size = static_cast<std::size_t>(n_ * (n_ + 1) / 2);
  SeriesExpansion monomials;
  monomials.powers = powers_;
  for_each_chunk(elapsed_.size(), kChunk, threads_, [&](int, std::size_t chunk, std::size_t begin, std::size_t end) {
    Eigen::MatrixXd S(n_, n_);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(n_);
    Eigen::VectorXd e(parameters());
    std::vector<double> coefficient(pieces);
    for (std::size_t sample = begin; sample < end; ++sample) {
      for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = perturbation_factor(k[i], l[i], elapsed_[sample]);
      for (std::size_t j = 0; j < pieces; ++j) coefficient[j] = monomials.coefficient(j, e);
      const double* piece = packed_.data() + sample * pieces * packed_size;
      for (Eigen::Index c = 0, index = 0; c < n_; ++c)
        for (Eigen::Index r = c; r < n_; ++r, ++index) {
          double sum = 0.0;
          for (std::size_t j = 0; j < pieces; ++j) sum += coefficient[j] * piece[j * packed_size + static_cast<std::size_t>(index)];
          S(r, c) = sum;
        }
      visit(chunk, static_cast<Eigen::Index>(sample), sigma_max_symmetric(solver, S));
    }
  });
}

Eigen::VectorXd SigmaMatch::sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const {
  Eigen::VectorXd out(samples());
  for_each_sigma(k, l, [&](std::size_t, Eigen::Index sample, double sigma) { out[sample] = sigma; });
  return out;
}

double SigmaMatch::residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l, Weighting weighting) const {
  std::vector<double> partial((elapsed_.size() + kChunk - 1) / kChunk, 0.0);
  for_each_sigma(k, l, [&](std::size_t chunk, Eigen::Index sample, double sigma) {
    const double difference = sigma - sigma_sdre_[sample];
    const double scaled = weighting == Weighting::relative ? difference / sigma_sdre_[sample] : difference;
    partial[chunk] += scaled * scaled;
  });
  double sum = 0.0;
  for (double value : partial) sum += value;
  return sum;
}

const std::vector<std::string>& fit_algorithms() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Algorithm& a : algorithms()) list.push_back(a.name);
    return list;
  }();
  return names;
}

void check_fit_options(const FitOptions& o, int parameters) {
  find_algorithm(o.algorithm);
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
  if (o.max_local_evaluations < 1 || o.max_global_evaluations < 1)
    throw Error("tuning: the evaluation limits must be >= 1");
}

FitResult fit(const SigmaMatch& match, const FitOptions& options) {
  const int p = match.parameters();
  check_fit_options(options, p);
  const Algorithm& algorithm = find_algorithm(options.algorithm);
  const auto start = std::chrono::steady_clock::now();

  std::vector<double> x(static_cast<std::size_t>(2 * p)), lower(x.size()), upper(x.size());
  const Eigen::VectorXd k0 = start_or_ones(options.k_start, p), l0 = start_or_ones(options.l_start, p);
  for (int i = 0; i < p; ++i) {
    const auto ki = static_cast<std::size_t>(i), li = static_cast<std::size_t>(p + i);
    x[ki] = k0[i];
    x[li] = l0[i];
    lower[ki] = options.k_lower;
    upper[ki] = options.k_upper;
    lower[li] = options.l_lower;
    upper[li] = options.l_upper;
  }
  Objective objective(match, options);
  FitResult result;
  result.start_residual = objective(x);
  if (algorithm.global) {
    nlopt::srand(options.seed);
    run_stage(objective, algorithm.id, lower, upper, x, options.max_global_evaluations, options.x_tolerance);
  }
  // Local polish (or the whole search): from the best point so far.
  result.stop_reason = run_stage(objective, algorithm.global ? nlopt::LN_BOBYQA : algorithm.id, lower, upper,
                                 objective.best_x, options.max_local_evaluations, options.x_tolerance);
  result.k = Eigen::Map<const Eigen::VectorXd>(objective.best_x.data(), p);
  result.l = Eigen::Map<const Eigen::VectorXd>(objective.best_x.data() + p, p);
  result.residual = objective.best;
  result.evaluations = objective.evaluations;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace thetad::tuning
