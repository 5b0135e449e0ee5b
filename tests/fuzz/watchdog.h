#pragma once
// Hang guards for the hostile-input tests: a test that would hang gets SIGALRM and fails
// instead of stalling the suite; secondsSince times the bounded waits.
#include <unistd.h>

#include <chrono>

namespace slide::test {

struct Watchdog {
  explicit Watchdog(unsigned seconds) { alarm(seconds); }
  ~Watchdog() { alarm(0); }
};

inline double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace slide::test
