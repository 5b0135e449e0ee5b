// Three slide-peer-sync processes in a private network namespace (unshare -n, loopback
// multicast): bundles published on each robot bus reach the other two exactly once and in
// order, across a kill -9 and restart of one daemon.
#include <gtest/gtest.h>

#include "daemon_harness.h"
#include "team/message_auth.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;
namespace fs = std::filesystem;

namespace {

const std::vector<int> kTeam = {1, 2, 3};
const char* kTeamUrl = "udpm://239.255.76.90:7690?ttl=0";

std::string robotUrl(int id) { return "udpm://239.255.76.67:" + std::to_string(7670 + id) + "?ttl=0"; }

// Runs this test again inside a fresh network namespace; true when this process is the inner one.
bool insideNetns() { return std::getenv("SLIDE_TEAM_NETNS") != nullptr; }

int runInNetns(const char* test) {
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  const pid_t pid = spawn({"unshare", "-n", "env", "SLIDE_TEAM_NETNS=1", exe, std::string("--gtest_filter=") + test});
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

bool waitFor(std::vector<std::unique_ptr<RobotBus>>& buses, const std::function<bool()>& done, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    for (auto& b : buses) b->poll();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

// Waits until a heartbeat from `robot` is heard on the team bus (its daemon is up).
bool waitHeartbeat(int robot, double seconds) {
  lcm::LCM team(kTeamUrl);
  struct H {
    int robot;
    bool seen = false;
    void on(const lcm::ReceiveBuffer*, const std::string&, const sync_heartbeat_t* m) { seen |= m->sender == robot; }
  } h{robot};
  team.subscribe("TEAM_HEARTBEAT", &H::on, &h);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!h.seen && std::chrono::steady_clock::now() < end) team.handleTimeout(50);
  return h.seen;
}

}  // namespace

TEST(PeerSyncProcesses, ThreeDaemonsExactlyOnceAcrossKillAndRestart) {
  const char* self = "PeerSyncProcesses.ThreeDaemonsExactlyOnceAcrossKillAndRestart";
  if (!insideNetns()) {
    if (geteuid() != 0) GTEST_SKIP() << "needs root for unshare -n";
    ASSERT_EQ(runInNetns(self), 0) << "the run inside the network namespace failed (see its output above)";
    return;
  }
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);
  const fs::path dir = fs::temp_directory_path() / ("slide_team_procs_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cfg = writeTestConfig(dir.string(), kTeamUrl);
  std::map<int, pid_t> pids;
  auto start = [&](int id) {
    pids[id] = spawn({daemonBinary(), "--config", cfg, "--robot", std::to_string(id), "--robot-url", robotUrl(id),
                      "--log-level", "warn"});
  };
  std::vector<std::unique_ptr<RobotBus>> buses;
  for (int id : kTeam) buses.push_back(std::make_unique<RobotBus>(robotUrl(id)));
  for (int id : kTeam) start(id);
  for (int id : kTeam) ASSERT_TRUE(waitHeartbeat(id, 5)) << "daemon " << id << " did not come up";

  const int n = 30;
  std::mt19937 rng(5);
  auto publish = [&](int id, int from, int to) {
    for (int s = from; s < to; ++s) {
      buses[static_cast<std::size_t>(id - 1)]->publish(randomBundle(rng, id, s));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      for (auto& b : buses) b->poll();
    }
  };
  auto count = [&](std::size_t i) { return buses[i]->got().size(); };
  for (int id : kTeam) publish(id, 0, n / 2);
  {
    // Garbage and forgeries on the team bus: random bytes, truncated messages, a wrong key.
    lcm::LCM team(kTeamUrl);
    std::vector<std::uint8_t> junk(300);
    for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
    for (const char* ch : {"TEAM_CHUNK", "TEAM_HEARTBEAT", "TEAM_ACK"}) team.publish(ch, junk.data(), 300);
    Chunk forged;
    forged.sender = 2;
    forged.counter = 1LL << 40;
    forged.origin = 2;
    forged.seq = n / 2;
    forged.data = encodeBundle(randomBundle(rng, 2, n / 2));
    authOf(2, {1, 2, 3}, "wrong-key").sign(forged);
    const sync_chunk_t m = toLcm(forged);
    team.publish("TEAM_CHUNK", &m);
    std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
    m.encode(buf.data(), 0, static_cast<int>(buf.size()));
    team.publish("TEAM_CHUNK", buf.data(), static_cast<unsigned>(buf.size() / 2));
  }
  EXPECT_TRUE(waitFor(buses, [&] { return count(0) == n && count(1) == n && count(2) == n; }, 20));
  // Robot 1's status message on its robot bus counts the forgery and the garbage.
  EXPECT_TRUE(waitFor(buses, [&] {
    const auto& d = buses[0]->drops();
    return d.count("bad_mac") && d.at("bad_mac") >= 1 && d.at("malformed") >= 1;
  }, 10)) << "no status message with the drops";

  // kill -9 robot 2's daemon; the others go on; then it comes back from its journal.
  stop(pids[2], SIGKILL);
  publish(1, n / 2, n);
  publish(3, n / 2, n);
  start(2);
  ASSERT_TRUE(waitHeartbeat(2, 5));
  publish(2, n / 2, n);
  const bool all = waitFor(buses, [&] { return count(0) == 2u * n && count(1) == 2u * n && count(2) == 2u * n; }, 30);
  // Linger a little: nothing more (no duplicate) may arrive.
  waitFor(buses, [] { return false; }, 1.0);
  EXPECT_TRUE(all);
  for (std::size_t i = 0; i < kTeam.size(); ++i)
    EXPECT_TRUE(deliveredExactlyOnceInOrder(buses[i]->got(), kTeam[i], kTeam, n));
  for (auto& [id, pid] : pids) EXPECT_TRUE(WIFEXITED(stop(pid, SIGTERM)));
  fs::remove_all(dir);
}
