#include "tuning/record.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/text_file.hpp"
#include "tuning/packed_series.hpp"
#include "core/parallel.hpp"
#include "tuning/sigma_fit.hpp"

namespace thetad::tuning {

namespace {

constexpr const char* kFormatLine = "# thetad tuning record v1: SDRE flight, sigma_max of P_SDRE at each kept sample";
constexpr const char* kScenarioPrefix = "# scenario: ";

std::string header(Eigen::Index n, Eigen::Index m) {
  std::string line = "t_s";
  for (Eigen::Index i = 0; i < n; ++i) line += ",x_" + std::to_string(i);
  for (Eigen::Index i = 0; i < m; ++i) line += ",u_" + std::to_string(i);
  return line + ",sigma_max_P";
}

}  // namespace

SdreRecorder::SdreRecorder(const SdreController& sdre, int every, Eigen::Index expected_samples, const Controller* shadow)
    : sdre_(sdre), shadow_(shadow ? shadow->clone() : nullptr), shadow_input_(sdre.settings().R.rows()), every_(every) {
  if (every < 1) throw Error("tuning: the record keeps every N-th controller sample, N >= 1, got " + std::to_string(every));
  const auto kept = static_cast<std::size_t>(expected_samples / every + 1);
  const auto m = static_cast<std::size_t>(sdre.settings().R.rows());
  time_.reserve(kept);
  states_.reserve(kept * static_cast<std::size_t>(sdre.settings().Q.rows()));
  inputs_.reserve(kept * m);
  if (shadow_) shadow_inputs_.reserve(kept * m);
}

SdreRecorder::SdreRecorder(const SdreRecorder& other)
    : Controller(other), sdre_(other.sdre_), shadow_(other.shadow_ ? other.shadow_->clone() : nullptr),
      shadow_input_(other.shadow_input_), every_(other.every_), sample_(other.sample_), time_(other.time_),
      states_(other.states_), inputs_(other.inputs_), shadow_inputs_(other.shadow_inputs_) {}

void SdreRecorder::reset(const Eigen::VectorXd& x0, double t0) {
  sdre_.reset(x0, t0);
  if (shadow_) shadow_->reset(x0, t0);
  sample_ = 0;
  time_.clear();
  states_.clear();
  inputs_.clear();
  shadow_inputs_.clear();
}

void SdreRecorder::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                           const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  sdre_.control(t, measured_state, reference, u);
  // Every sample, kept or not: the shadow's fixed point starts from its own previous input.
  if (shadow_) shadow_->control(t, measured_state, reference, shadow_input_);
  if (sample_++ % every_ != 0) return;
  time_.push_back(t);
  states_.insert(states_.end(), measured_state.begin(), measured_state.end());
  inputs_.insert(inputs_.end(), u.begin(), u.end());
  if (shadow_) shadow_inputs_.insert(shadow_inputs_.end(), shadow_input_.begin(), shadow_input_.end());
}

TuningRecord SdreRecorder::finish(const std::string& scenario, int threads) const {
  if (time_.empty()) throw Error("tuning: the SDRE flight recorded no sample");
  const auto n = sdre_.settings().Q.rows(), m = sdre_.settings().R.rows();
  TuningRecord record;
  record.scenario = scenario;
  record.time = time_;
  const Eigen::Index K = record.size();
  record.states = Eigen::Map<const Eigen::MatrixXd>(states_.data(), n, K);
  record.inputs = Eigen::Map<const Eigen::MatrixXd>(inputs_.data(), m, K);
  if (shadow_) record.shadow_inputs = Eigen::Map<const Eigen::MatrixXd>(shadow_inputs_.data(), m, K);
  record.sigma_sdre.resize(K);
  for_each_chunk(static_cast<std::size_t>(K), 64, threads, [&](int, std::size_t, std::size_t begin, std::size_t end) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(n);
    for (auto k = static_cast<Eigen::Index>(begin); k < static_cast<Eigen::Index>(end); ++k)
      record.sigma_sdre[k] = sigma_max_symmetric(
          solver, sdre_.value_matrix(record.states.col(k), record.inputs.col(k), record.time[static_cast<std::size_t>(k)]));
  });
  return record;
}

TuningRecord record_sdre_flight(const Flight& flight, const SdreController& sdre, int every, int threads,
                                Progress* progress, const Controller* shadow) {
  const sim::SimulationSettings& settings = flight.settings();
  const auto samples = static_cast<Eigen::Index>(std::llround(settings.duration / settings.controller_period()));
  PreparedController prepared{{"sdre-record", "sdre", {}, {}, {}}, std::make_unique<SdreRecorder>(sdre, every, samples, shadow), {}, {}};
  const RunResult run = flight.fly(prepared, progress, "sdre (record):");
  if (!run.completed())
    throw Error("tuning: the SDRE flight of " + flight.scenario().name + " diverged (" + run.summary.reason +
                "); there is no full trajectory to tune on");
  return dynamic_cast<const SdreRecorder&>(*prepared.controller).finish(flight.scenario().name, threads);
}

Eigen::MatrixXd sdre_value_matrices(const SdreController& sdre, const TuningRecord& record, int threads) {
  const Eigen::Index n = record.states.rows();
  Eigen::MatrixXd packed(n * (n + 1) / 2, record.size());
  for_each_chunk(static_cast<std::size_t>(record.size()), 64, threads, [&](int, std::size_t, std::size_t begin, std::size_t end) {
    for (auto k = static_cast<Eigen::Index>(begin); k < static_cast<Eigen::Index>(end); ++k)
      pack_lower(sdre.value_matrix(record.states.col(k), record.inputs.col(k), record.time[static_cast<std::size_t>(k)]),
                 packed.col(k).data());
  });
  return packed;
}

std::string record_csv(const TuningRecord& record) {
  std::string text = std::string(kFormatLine) + "\n" + kScenarioPrefix + record.scenario + "\n" +
                     header(record.states.rows(), record.inputs.rows()) + "\n";
  char number[32];
  const auto append = [&](double value, bool first) {
    std::snprintf(number, sizeof number, "%.17g", value);
    if (!first) text += ',';
    text += number;
  };
  for (Eigen::Index k = 0; k < record.size(); ++k) {
    append(record.time[static_cast<std::size_t>(k)], true);
    for (Eigen::Index i = 0; i < record.states.rows(); ++i) append(record.states(i, k), false);
    for (Eigen::Index i = 0; i < record.inputs.rows(); ++i) append(record.inputs(i, k), false);
    append(record.sigma_sdre[k], false);
    text += '\n';
  }
  return text;
}

void write_record(const std::filesystem::path& file, const TuningRecord& record) {
  write_file_atomically(file, record_csv(record));
}

TuningRecord read_record(const std::filesystem::path& file, Eigen::Index n, Eigen::Index m) {
  std::istringstream in([&] {
    try {
      return read_text_file(file);
    } catch (const Error& error) {
      throw Error(std::string("tuning record: ") + error.what());
    }
  }());
  const std::string source = file.string();
  const auto fail = [&](long line, const std::string& why) {
    throw Error(source + ":" + std::to_string(line) + ": " + why);
  };
  std::string line;
  long number = 1;
  if (!std::getline(in, line) || line != kFormatLine) fail(number, "not a thetad tuning record (first line must be '" + std::string(kFormatLine) + "')");
  ++number;
  if (!std::getline(in, line) || line.rfind(kScenarioPrefix, 0) != 0) fail(number, "expected '# scenario: NAME'");
  TuningRecord record;
  record.scenario = line.substr(std::strlen(kScenarioPrefix));
  ++number;
  const std::string expected = header(n, m);
  if (!std::getline(in, line) || line != expected)
    fail(number, "wrong columns for a plant with " + std::to_string(n) + " states and " + std::to_string(m) +
                     " inputs: expected '" + expected + "'");

  const auto columns = static_cast<std::size_t>(1 + n + m + 1);
  std::vector<double> values;
  while (std::getline(in, line)) {
    ++number;
    const char* cursor = line.c_str();
    for (std::size_t c = 0; c < columns; ++c) {
      char* end = nullptr;
      const double value = std::strtod(cursor, &end);
      if (end == cursor) fail(number, "column " + std::to_string(c + 1) + ": not a number");
      if (!std::isfinite(value)) fail(number, "column " + std::to_string(c + 1) + ": not finite");
      const char expected_separator = c + 1 < columns ? ',' : '\0';
      if (*end != expected_separator)
        fail(number, c + 1 < columns ? "only " + std::to_string(c + 1) + " of " + std::to_string(columns) + " columns"
                                     : "more than " + std::to_string(columns) + " columns");
      values.push_back(value);
      cursor = end + 1;
    }
    const double t = values[values.size() - columns];
    if (!record.time.empty() && !(t > record.time.back())) fail(number, "time does not increase");
    record.time.push_back(t);
  }
  if (record.time.empty()) fail(number, "no samples");

  const Eigen::Index K = record.size();
  const Eigen::Map<const Eigen::MatrixXd> table(values.data(), static_cast<Eigen::Index>(columns), K);
  record.states = table.middleRows(1, n);
  record.inputs = table.middleRows(1 + n, m);
  record.sigma_sdre = table.row(1 + n + m).transpose();
  return record;
}

}  // namespace thetad::tuning
