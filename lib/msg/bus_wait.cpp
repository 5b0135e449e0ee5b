#include "msg/bus_wait.h"

#include <sys/select.h>

#include <algorithm>
#include <lcm/lcm-cpp.hpp>
#include <vector>

namespace slide::msg {

void handleAny(const std::vector<lcm::LCM*>& buses, std::int64_t timeout_us) {
  fd_set fds;
  FD_ZERO(&fds);
  int max_fd = -1;
  for (lcm::LCM* b : buses) {
    FD_SET(b->getFileno(), &fds);
    max_fd = std::max(max_fd, b->getFileno());
  }
  timeout_us = std::max<std::int64_t>(0, timeout_us);
  timeval tv{static_cast<time_t>(timeout_us / 1000000), static_cast<suseconds_t>(timeout_us % 1000000)};
  if (select(max_fd + 1, &fds, nullptr, nullptr, &tv) <= 0) return;
  for (lcm::LCM* b : buses)
    if (FD_ISSET(b->getFileno(), &fds)) b->handle();
}

}  // namespace slide::msg
