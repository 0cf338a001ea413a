#include "campaigns/campaign_runner.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "campaigns/campaign_progress.hpp"
#include "campaigns/campaign_store.hpp"
#include "campaigns/campaign_worker.hpp"
#include "campaigns/mpi_session.hpp"
#include "core/error.hpp"

namespace thetad {

namespace {

// The runs whose log is kept (--keep-logs).
std::optional<KeptLogs> kept_logs(const CampaignOptions& options) {
  if (!options.keep_logs) return std::nullopt;
  if (*options.keep_logs < 0) throw Error("--keep-logs " + std::to_string(*options.keep_logs) + ": must be >= 0");
  return KeptLogs{*options.keep_logs, options.out};
}

// The runs still to fly, handed out in run-index order to whoever asks first.
class RunDispenser {
 public:
  explicit RunDispenser(std::vector<std::int64_t> pending) : pending_(std::move(pending)) {}
  std::optional<std::int64_t> next() {
    const std::size_t i = next_.fetch_add(1);
    if (i >= pending_.size()) return std::nullopt;
    return pending_[i];
  }
  std::size_t size() const { return pending_.size(); }

 private:
  std::vector<std::int64_t> pending_;
  std::atomic<std::size_t> next_{0};
};

// Worker threads, each with its own CampaignWorker, flying what the dispenser hands out; the
// finished records wait in a queue for the writer.
class ThreadPool {
 public:
  ThreadPool(const Campaign& campaign, const CampaignOptions& options, RunDispenser& dispenser, int threads) {
    for (int i = 0; i < threads; ++i) {
      threads_.emplace_back([this, &campaign, &options, &dispenser] {
        // A stop (the writer failed or was interrupted) abandons the flights under way.
        const auto abandon_when_stopped = [this](double) {
          if (stop_) throw Error("campaign stopped");
        };
        try {
          CampaignWorker worker(campaign, options.timing, kept_logs(options));
          while (!stop_) {
            const auto index = dispenser.next();
            if (!index) break;
            RunRecord record = worker.fly(*index, abandon_when_stopped);
            const std::lock_guard lock(mutex_);
            finished_.push_back(std::move(record));
            ready_.notify_one();
          }
        } catch (...) {
          const std::lock_guard lock(mutex_);
          if (!failure_) failure_ = std::current_exception();
          stop_ = true;
          ready_.notify_one();
        }
      });
    }
  }
  ~ThreadPool() {
    stop_ = true;
    for (auto& thread : threads_) thread.join();
  }
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // The records finished so far, waiting up to `wait` for the first; rethrows a worker's failure.
  std::vector<RunRecord> take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, wait, [this] { return !finished_.empty() || failure_; });
    if (failure_) std::rethrow_exception(failure_);
    return std::exchange(finished_, {});
  }

 private:
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<RunRecord> finished_;
  std::exception_ptr failure_;
  std::atomic<bool> stop_{false};
};

int default_jobs(bool mpi) {
  if (mpi) return 1;  // one rank per core: mpirun places them
  const unsigned cores = std::thread::hardware_concurrency();
  return cores == 0 ? 1 : static_cast<int>(cores);
}

// Rank 0 (or the only process): flies with local threads, serves the other ranks, writes.
CampaignOutcome coordinate(const Campaign& campaign, const CampaignOptions& options, MpiSession* mpi) {
  // Every flight and controller built once: a bad cell or settings block fails before anything
  // flies or is written.
  CampaignWorker check(campaign, options.timing, kept_logs(options));
  check.prepare_all();
  std::filesystem::create_directories(options.out);
  CampaignStore store(store_file(options.out), campaign, options.shard,
                      options.resume ? CampaignStore::Open::resume : CampaignStore::Open::create, check.provenance());

  const std::set<std::int64_t> stored = store.stored();
  std::vector<std::int64_t> pending;
  std::int64_t runs = 0;
  for (std::int64_t i = 0; i < campaign.run_count(); ++i) {
    if (!options.shard.holds(i)) continue;
    ++runs;
    if (!stored.contains(i)) pending.push_back(i);
  }
  CampaignProgress progress(options.progress, campaign.name, runs, runs - static_cast<std::int64_t>(pending.size()),
                            options.observer);
  RunDispenser dispenser(std::move(pending));
  const int remote = mpi ? mpi->size() - 1 : 0;
  int stopped = 0;
  ThreadPool pool(campaign, options, dispenser, options.jobs > 0 ? options.jobs : default_jobs(mpi != nullptr));
  std::size_t written = 0;
  // With other ranks to serve, the writer wakes every millisecond to answer them promptly.
  const std::chrono::milliseconds wait(mpi ? 1 : 250);
  while (written < dispenser.size() || stopped < remote) {
    std::vector<RunRecord> batch = pool.take(wait);
    while (mpi) {
      auto request = mpi->poll();
      if (!request) break;
      if (!request->error.empty()) throw Error("MPI rank " + std::to_string(request->rank) + ": " + request->error);
      if (request->record) batch.push_back(std::move(*request->record));
      const auto index = dispenser.next();
      if (!index) ++stopped;
      mpi->answer(request->rank, index);
    }
    store.write(batch);
    for (const RunRecord& record : batch) progress.add(record.completed());
    progress.tick();
    written += batch.size();
  }
  progress.finish();
  return {runs, progress.flown(), progress.not_completed(), true};
}

// Any other rank: flies the indices rank 0 hands out until it says stop.
CampaignOutcome serve(const Campaign& campaign, const CampaignOptions& options, MpiSession& mpi) {
  CampaignWorker worker(campaign, options.timing, kept_logs(options));
  std::optional<RunRecord> finished;
  CampaignOutcome outcome;
  outcome.writer = false;
  try {
    while (const auto index = mpi.request(finished)) {
      finished = worker.fly(*index);
      ++outcome.flown;
      if (!finished->completed()) ++outcome.not_completed;
    }
  } catch (const std::exception& error) {
    mpi.report_error(error.what());
    throw;
  }
  return outcome;
}

}  // namespace

CampaignOutcome run_campaign(const Campaign& campaign, const CampaignOptions& options) {
  if (!MpiSession::launched_by_mpirun()) return coordinate(campaign, options, nullptr);
  MpiSession mpi;
  if (mpi.rank() != 0) return serve(campaign, options, mpi);
  try {
    return coordinate(campaign, options, &mpi);
  } catch (const std::exception& error) {
    if (mpi.size() == 1) throw;
    // The other ranks wait on rank 0: end them all, after saying why.
    std::fprintf(stderr, "thetad: error: %s\n", error.what());
    mpi.abort(1);
  }
}

}  // namespace thetad
