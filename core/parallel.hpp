#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace thetad {

// Runs work(worker, chunk, begin, end) for the chunks [c·chunk_size, min((c+1)·chunk_size, count))
// of 0 … count−1, chunk c on worker c mod workers. The chunks do not depend on the number of
// workers, so a caller that keeps one result per chunk and combines them in chunk order gets
// bit-identical results for any number of workers and any scheduling. The first exception thrown
// by a worker is rethrown here after every worker has finished.
inline void for_each_chunk(std::size_t count, std::size_t chunk_size, int workers,
                           const std::function<void(int worker, std::size_t chunk, std::size_t begin, std::size_t end)>& work) {
  const std::size_t chunks = (count + chunk_size - 1) / chunk_size;
  const auto run = [&](int worker, std::exception_ptr& failure) {
    try {
      for (std::size_t c = static_cast<std::size_t>(worker); c < chunks; c += static_cast<std::size_t>(workers))
        work(worker, c, c * chunk_size, std::min(count, (c + 1) * chunk_size));
    } catch (...) {
      failure = std::current_exception();
    }
  };
  std::vector<std::exception_ptr> failures(static_cast<std::size_t>(workers));
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(run, w, std::ref(failures[static_cast<std::size_t>(w)]));
  run(0, failures[0]);  // the calling thread is worker 0
  for (std::thread& thread : threads) thread.join();
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

}  // namespace thetad
