// A stop request (SIGINT/SIGTERM, docs/robustness.md "Signals"): the CLI's signal thread
// sets it; long computations poll it and throw Interrupted, so that their outputs'
// temporaries are removed while the stack unwinds. The flag is process-wide: one
// command runs per process.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>
#include <string_view>

namespace abu {

/// Thrown by a computation that saw a stop request. The CLI exits 128 + signal.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal, std::string_view where);
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// The flag itself (for code that takes a `const std::atomic<bool>*`, e.g. the map driver).
std::atomic<bool>& stop_flag();
/// Records a stop request by `signal` (SIGINT, SIGTERM; 0 for a request not from a signal).
void request_stop(int signal) noexcept;
/// True once a stop was requested.
inline bool stop_requested() noexcept { return stop_flag().load(std::memory_order_relaxed); }
/// The signal of the stop request (0 if none or not from a signal).
int stop_signal() noexcept;
/// Clears the request (tests; a command runs once per process otherwise).
void clear_stop() noexcept;
/// Throws Interrupted naming `where` if a stop was requested: call it at least once a
/// second of work (every step, point or cell of a long loop).
inline void throw_if_stopped(std::string_view where) {
  if (stop_requested()) throw Interrupted(stop_signal(), where);
}

}  // namespace abu
