#include "app/stop_signal.h"

#include <csignal>

namespace slide::app {

namespace {
std::atomic<bool> g_stop{false};  // lock-free, so a signal handler may set it
static_assert(std::atomic<bool>::is_always_lock_free);
volatile std::sig_atomic_t g_write = 0;
}  // namespace

void installStopHandlers() {
  std::signal(SIGINT, [](int) { g_stop.store(true); });
  std::signal(SIGTERM, [](int) { g_stop.store(true); });
}

bool stopRequested() { return g_stop.load(); }

const std::atomic<bool>* stopFlag() { return &g_stop; }

void installWriteHandler() {
  std::signal(SIGUSR1, [](int) { g_write = 1; });
}

bool takeWriteRequest() {
  if (!g_write) return false;
  g_write = 0;
  return true;
}

}  // namespace slide::app
