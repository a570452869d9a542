#include "abu/core/cancel.hpp"

#include <fmt/format.h>

#include <csignal>
#include <cstring>

namespace abu {

namespace {
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == 0) return "a stop request";
  return fmt::format("signal {}", signal);
}
}  // namespace

Interrupted::Interrupted(int signal, std::string_view where)
    : std::runtime_error(fmt::format("interrupted by {} during {}", signal_name(signal), where)), signal_(signal) {}

std::atomic<bool>& stop_flag() { return g_stop; }

void request_stop(int signal) noexcept {
  int expected = 0;
  g_signal.compare_exchange_strong(expected, signal);
  g_stop.store(true);
}

int stop_signal() noexcept { return g_signal.load(); }

void clear_stop() noexcept {
  g_signal.store(0);
  g_stop.store(false);
}

}  // namespace abu
