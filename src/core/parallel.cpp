#include "abu/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace abu {

void for_each_index(int count, int threads, const std::function<bool(int)>& body) {
  std::atomic<int> next{0};
  std::mutex guard;
  std::exception_ptr error;
  const auto work = [&] {
    for (int k = next++; k < count; k = next++) {
      try {
        if (!body(k)) {
          next = count;
          return;
        }
      } catch (...) {
        const std::lock_guard lock(guard);
        if (!error) error = std::current_exception();
        next = count;
        return;
      }
    }
  };
  const int wanted = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> workers;
  for (int t = 1; t < wanted && t < count; ++t) workers.emplace_back(work);
  work();
  for (auto& t : workers) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace abu
