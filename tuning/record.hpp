#pragma once

// Step 1 of the k_i, l_i fit (docs/model.md §8.1): fly the SDRE controller and keep, at every kept
// controller sample, the time, the state it saw, the input at which its F, B were evaluated and
// σ_max of its P. Saved as CSV so that fits rerun without re-flying.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "controllers/sdre.hpp"
#include "core/helicopter/model_options.hpp"
#include "core/sim/simulator.hpp"
#include "experiment/flight.hpp"
#include "experiment/progress.hpp"

namespace thetad::tuning {

struct TuningRecord {
  std::string scenario;       // name of the flown scenario: a reused record must match it
  std::vector<double> time;   // t_k (s), the simulator's time of the controller sample
  Eigen::MatrixXd states;     // n × K: the measured state x_k the SDRE saw
  Eigen::MatrixXd inputs;     // m × K: the input u_k at which F(x_k; u_k), B(x_k; u_k) are taken
  Eigen::VectorXd sigma_sdre; // K: σ_max(P_SDRE(x_k; u_k)) of Eq. (37)
  // m × K: what a shadow controller commanded at each kept sample (empty without one; not in the CSV).
  Eigen::MatrixXd shadow_inputs;

  Eigen::Index size() const { return static_cast<Eigen::Index>(time.size()); }
};

// Flies like the wrapped SDRE and keeps the measured state and the applied input of every
// `every`-th controller sample. The applied input is the converged fixed point of docs/model.md §6.2, so
// the record's P and the θ–D's ΣT_i are both taken at the same (x_k; u_k): the fit compares the
// two value matrices of one SDC, whatever the fixed point's last correction was. A Controller so
// that anything that flies controllers (the command line's progress display) flies it too.
class SdreRecorder final : public Controller {
 public:
  // `expected_samples`: the run's controller samples, so that control() never allocates.
  // `shadow` (optional, copied): a controller that computes its own input at every sample from
  // the same measurement and reference without flying it, e.g. the θ–D in the SDRE's place.
  SdreRecorder(const SdreController& sdre, int every, Eigen::Index expected_samples, const Controller* shadow = nullptr);
  SdreRecorder(const SdreRecorder& other);

  std::string name() const override { return sdre_.name(); }
  std::unique_ptr<Controller> clone() const override { return std::make_unique<SdreRecorder>(*this); }
  void reset(const Eigen::VectorXd& x0, double t0) override;
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;
  std::vector<std::pair<std::string, double>> counters() const override { return sdre_.counters(); }

  // The kept samples with σ_max(P) from a cold CARE solve at each (x_k; u_k), spread over
  // `threads` threads. Throws thetad::Error when a CARE fails or nothing was recorded.
  TuningRecord finish(const std::string& scenario, int threads) const;

 private:
  SdreController sdre_;
  std::unique_ptr<Controller> shadow_;
  Eigen::VectorXd shadow_input_;
  int every_;
  long sample_ = 0;
  std::vector<double> time_;
  std::vector<double> states_, inputs_, shadow_inputs_;  // column-major n × K and m × K as they grow
};

// Flies `sdre` (wrapped in an SdreRecorder) through `flight` and returns the record, keeping every
// `every`-th sample, σ_max by cold solves on `threads` threads. Throws thetad::Error if the flight
// diverges: a record that stops early would tune on a partial trajectory without saying so.
// `shadow` as for SdreRecorder.
TuningRecord record_sdre_flight(const Flight& flight, const SdreController& sdre, int every = 10, int threads = 2,
                                Progress* progress = nullptr, const Controller* shadow = nullptr);

// P_SDRE(x_k; u_k) of every sample by cold CARE solves on `threads` threads, as packed lower
// triangles (pack_lower), one column per sample: what the per-entry objective compares ΣT_i with.
Eigen::MatrixXd sdre_value_matrices(const SdreController& sdre, const TuningRecord& record, int threads);

// CSV: two comment lines (format, scenario), then the header t_s,x_0..x_{n-1},u_0..u_{m-1},sigma_max_P
// and one row per sample in %.17g (exact round trip). Written atomically.
std::string record_csv(const TuningRecord& record);
void write_record(const std::filesystem::path& file, const TuningRecord& record);
// Reads a record written by write_record for a plant with n states and m inputs. Throws
// thetad::Error naming the file and line for a missing file, a wrong header (column names or
// count), a short row, a non-number, a non-finite value, non-increasing time or no rows.
TuningRecord read_record(const std::filesystem::path& file, Eigen::Index n, Eigen::Index m);

}  // namespace thetad::tuning
