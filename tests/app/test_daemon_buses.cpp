// Every daemon started with --robot 2 and nothing else about its bus speaks on robot 2's bus,
// udpm://239.255.76.67:7669 (README: 7667+N), and nothing of it reaches port 7667 (robot 0's
// bus and LCM's default). Each daemon's own messages are caught on the bus, stamped robot 2: a
// daemon that ignored --robot, or kept another default, fails here whatever it logs. All six run
// at once in a private network namespace (unshare -n; needs root).
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>

#include "slide/daemon_status_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/peer_sync_status_t.hpp"
#include "slide/stream_status_t.hpp"

extern char** environ;

namespace {
const char* kRobot2Bus = "udpm://239.255.76.67:7669?ttl=0&recv_buf_size=4194304";
const char* kPort7667 = "udpm://239.255.76.67:7667?ttl=0";

pid_t spawn(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  return pid;
}

template <typename M>
bool decode(const lcm::ReceiveBuffer* rb, M& m) {
  return m.decode(rb->data, 0, static_cast<int>(rb->data_size)) == static_cast<int>(rb->data_size);
}

// Which daemon sent a message, and for which robot: "segmenter@2".
struct Heard {
  std::set<std::string> senders;
  std::set<std::string> channels;
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    channels.insert(channel);
    if (channel == "DAEMON_STATUS") {
      slide::daemon_status_t m;
      if (decode(rb, m)) senders.insert(m.daemon + "@" + std::to_string(m.robot));
    } else if (channel == "OBJECT_MAP") {
      slide::object_map_t m;
      if (decode(rb, m)) senders.insert("optimizer@" + std::to_string(m.robot));
    } else if (channel == "PEER_SYNC_STATUS") {
      slide::peer_sync_status_t m;
      if (decode(rb, m)) senders.insert("peer_sync@" + std::to_string(m.robot));
    } else if (channel == "SENSOR_STATUS") {
      slide::stream_status_t m;
      if (decode(rb, m)) senders.insert("sensor_driver@" + std::to_string(m.robot));
    }
  }
};
}  // namespace

TEST(DaemonBuses, RobotOptionAlonePutsEveryDaemonOnItsRobotsBus) {
  ASSERT_EQ(unshare(CLONE_NEWNET), 0) << "unshare(CLONE_NEWNET) failed (tests run as root)";
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);
  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/";
  const std::string tmp = ::testing::TempDir() + "daemon_buses_" + std::to_string(getpid());
  std::filesystem::remove_all(tmp);
  ASSERT_EQ(std::system((bin + "slide-team-keys --team 0,1,2 --out " + tmp + "/keys >/dev/null").c_str()), 0);

  lcm::LCM robot2(kRobot2Bus), robot0(kPort7667);
  ASSERT_TRUE(robot2.good() && robot0.good());
  Heard on2, on0;
  robot2.subscribe(".*", &Heard::on, &on2);
  robot0.subscribe(".*", &Heard::on, &on0);
  auto pump = [&](double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      robot2.handleTimeout(10);
      robot0.handleTimeout(10);
    }
  };

  const std::vector<std::string> quiet{"--robot", "2", "--log-level", "error"};
  auto with = [&](std::vector<std::string> head, std::vector<std::string> tail = {}) {
    head.insert(head.end(), quiet.begin(), quiet.end());
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
  };
  std::map<std::string, pid_t> pids{
      {"segmenter", spawn(with({bin + "slide-segmenter"}))},
      {"tracker", spawn(with({bin + "slide-tracker"}))},
      {"optimizer", spawn(with({bin + "slide-optimizer"}))},
      {"loop_closer", spawn(with({bin + "slide-loop-closer"}))},
      {"peer_sync", spawn(with({bin + "slide-peer-sync"},
                               {"--state-dir", tmp + "/state", "--team-key-file", tmp + "/keys/robot2.keys"}))},
      // No dataset there: the driver stops at once and says FAILED on its bus.
      {"sensor_driver", spawn(with({bin + "slide-sensor-driver", tmp + "/no-such-dataset"}))}};
  for (const auto& [name, pid] : pids) ASSERT_GT(pid, 0) << name;
  pump(3.0);
  for (const auto& [name, pid] : pids) kill(pid, SIGTERM);  // the last status, map and counts go out at stop
  pump(2.0);
  for (const auto& [name, pid] : pids) waitpid(pid, nullptr, 0);
  std::filesystem::remove_all(tmp);

  for (const std::string name : {"segmenter", "tracker", "optimizer", "loop_closer", "peer_sync", "sensor_driver"})
    EXPECT_TRUE(on2.senders.count(name + "@2")) << name << " said nothing as robot 2 on " << kRobot2Bus;
  for (const std::string& s : on2.senders) EXPECT_EQ(s.substr(s.size() - 2), "@2") << s;
  EXPECT_TRUE(on0.channels.empty()) << "traffic on port 7667, e.g. " << *on0.channels.begin();
}
