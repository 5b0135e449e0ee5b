#pragma once
// Starting and stopping slide-peer-sync processes, and talking to their robot buses, for the
// multi-process tests. The tests run inside network namespaces they create themselves.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "slide/keypose_bundle_t.hpp"
#include "slide/peer_sync_status_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "team_test_util.h"
#include "../../daemons/peer_sync/team_msg.h"

namespace slide::team::testing {

inline std::string daemonBinary() { return std::string(SLIDE_BINARY_DIR) + "/bin/slide-peer-sync"; }

// A config with quick timings for tests, and key files <dir>/keys/robot<id>.keys derived from
// the master secret "test-team-key".
inline std::string writeTestConfig(const std::string& dir, const std::string& team_url) {
  const std::string path = dir + "/peer_sync.yaml";
  std::filesystem::create_directories(dir + "/keys");
  for (std::int32_t id : {1, 2, 3})
    writeTeamKeys(dir + "/keys/robot" + std::to_string(id) + ".keys", id, derivePairKeys("test-team-key", id, {1, 2, 3}));
  std::ofstream(path) << "team: [1, 2, 3]\n"
                         "team_key_file: \"" << dir << "/keys/robot{robot}.keys\"\n"
                         "robot_url: \"udpm://239.255.76.67:7667?ttl=0\"\n"
                         "team_url: \"" << team_url << "\"\n"
                         "state_dir: \"" << dir << "\"\n"
                         "channels: {own_bundle: KEYPOSE_BUNDLE, own_map: OWN_MAP, peer_bundle: PEER_BUNDLE,\n"
                         "           peer_map: PEER_MAP, heartbeat: TEAM_HEARTBEAT, chunk: TEAM_CHUNK, ack: TEAM_ACK}\n"
                         "tick_period_s: 0.02\nstats_period_s: 3\nheartbeat_period_s: 0.3\nack_delay_s: 0.05\n"
                         "resend_timeout_s: 0.6\nrelay_delay_s: 0.6\npeer_timeout_s: 2.0\nbundle_hold_s: 0.3\n"
                         "rate_limit_bytes_per_s: 200000\nburst_bytes: 50000\n";
  return path;
}

// Runs `argv` as a child process (stderr appended to `log` when given).
inline pid_t spawn(const std::vector<std::string>& argv, const std::string& log = "") {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!log.empty() && !std::freopen(log.c_str(), "a", stderr)) _exit(126);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    _exit(127);
  }
  return pid;
}

inline int stop(pid_t pid, int sig) {
  if (pid <= 0) return -1;
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

// Listens to one robot bus: PEER_BUNDLE deliveries in arrival order.
class RobotBus {
 public:
  explicit RobotBus(const std::string& url) : lcm_(url) {
    lcm_.subscribe("PEER_BUNDLE", &RobotBus::onBundle, this);
    lcm_.subscribe("PEER_SYNC_STATUS", &RobotBus::onStatus, this);
  }
  // Drop counts by reason in the latest status message (empty before the first).
  const std::map<std::string, std::int64_t>& drops() const { return drops_; }
  bool good() { return lcm_.good(); }
  void publish(const KeyPoseBundle& b) {
    const keypose_bundle_t m = msg::toLcm(b);
    lcm_.publish("KEYPOSE_BUNDLE", &m);
  }
  void poll() {
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  const std::vector<std::pair<int, int>>& got() const { return got_; }

 private:
  void onBundle(const lcm::ReceiveBuffer*, const std::string&, const keypose_bundle_t* m) {
    got_.emplace_back(m->header.robot, m->header.seq);
  }
  void onStatus(const lcm::ReceiveBuffer*, const std::string&, const peer_sync_status_t* m) {
    drops_.clear();
    for (int i = 0; i < m->num_drops; ++i) drops_[m->drop_reasons[static_cast<std::size_t>(i)]] = m->drop_counts[static_cast<std::size_t>(i)];
  }
  lcm::LCM lcm_;
  std::vector<std::pair<int, int>> got_;
  std::map<std::string, std::int64_t> drops_;
};

// Every origin other than `self` delivered seqs 0..n-1 exactly once, in order.
inline ::testing::AssertionResult deliveredExactlyOnceInOrder(const std::vector<std::pair<int, int>>& got, int self,
                                                              const std::vector<int>& team, int n) {
  std::map<int, std::vector<int>> per;
  for (const auto& [o, s] : got) per[o].push_back(s);
  for (int o : team) {
    if (o == self) {
      if (per.count(o)) return ::testing::AssertionFailure() << "robot " << self << " got its own bundles back";
      continue;
    }
    std::vector<int> expect(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) expect[static_cast<std::size_t>(i)] = i;
    if (per[o] != expect) {
      std::string seqs;
      for (int s : per[o]) seqs += " " + std::to_string(s);
      return ::testing::AssertionFailure() << "robot " << self << " from " << o << ": got " << per[o].size()
                                           << " deliveries, expected 0.." << n - 1 << ":" << seqs;
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace slide::team::testing
