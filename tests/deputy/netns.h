#pragma once
// Moves the calling test process into a private network namespace with multicast on
// loopback, so LCM traffic of a test never leaves it. Needs root (CAP_SYS_ADMIN).
#include <sched.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace slide::test {

// Returns an empty string on success, else why it failed.
inline std::string enterPrivateNetns() {
  static std::string result = [] {
    if (geteuid() != 0) return std::string("not root");
    if (unshare(CLONE_NEWNET) != 0) return std::string("unshare(CLONE_NEWNET) failed");
    if (std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo") != 0)
      return std::string("cannot set up loopback multicast");
    return std::string();
  }();
  return result;
}

}  // namespace slide::test
