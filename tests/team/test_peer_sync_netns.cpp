// Three robots in three network namespaces, 30% loss on every link and links cut half the
// time, one daemon killed with -9 and restarted: every bundle reaches every other robot exactly
// once and in order. The kernel here has no netem or packet filters, so the namespaces are
// joined by a lossy user-space hub: it hears the team bus (loopback multicast, ttl=0) in each
// namespace and repeats every datagram into the others with 30% loss and scheduled cuts.
// Everything runs inside a private namespace of its own; nothing leaves it.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sched.h>
#include <sys/socket.h>

#include <atomic>
#include <deque>
#include <mutex>

#include "daemon_harness.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;
namespace fs = std::filesystem;

namespace {

const std::vector<int> kTeam = {1, 2, 3};
const char* kTeamGroup = "239.255.76.91";
const int kTeamPort = 7691;
const char* kTeamUrl = "udpm://239.255.76.91:7691?ttl=0";
std::string robotUrl(int id) { return "udpm://239.255.76.67:" + std::to_string(7680 + id) + "?ttl=0"; }

int sh(const std::string& cmd) { return std::system(cmd.c_str()); }

bool enterNetns(const std::string& ns) {
  const int fd = open(("/var/run/netns/" + ns).c_str(), O_RDONLY);
  if (fd < 0) return false;
  const bool ok = setns(fd, CLONE_NEWNET) == 0;
  close(fd);
  return ok;
}

// Repeats team-bus datagrams between the robots' namespaces with loss and link cuts.
class LossyHub {
 public:
  LossyHub(std::vector<std::string> namespaces, double loss, std::function<bool(int, int)> link_up)
      : ns_(std::move(namespaces)), loss_(loss), link_up_(std::move(link_up)), queues_(ns_.size()) {
    for (std::size_t i = 0; i < ns_.size(); ++i) threads_.emplace_back([this, i] { loop(i); });
  }
  ~LossyHub() {
    stop_ = true;
    for (auto& t : threads_) t.join();
  }
  int ready() const { return ready_; }
  std::uint64_t forwarded() const { return forwarded_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  void loop(std::size_t i) {
    if (!enterNetns(ns_[i])) return;
    const int rx = socket(AF_INET, SOCK_DGRAM, 0), tx = socket(AF_INET, SOCK_DGRAM, 0);
    int one = 1;
    setsockopt(rx, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in any{};
    any.sin_family = AF_INET;
    any.sin_port = htons(kTeamPort);
    any.sin_addr.s_addr = htonl(INADDR_ANY);
    ip_mreq mreq{};
    inet_pton(AF_INET, kTeamGroup, &mreq.imr_multiaddr);
    mreq.imr_interface.s_addr = htonl(INADDR_ANY);
    unsigned char ttl = 0, loop_on = 1;
    setsockopt(tx, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
    setsockopt(tx, IPPROTO_IP, IP_MULTICAST_LOOP, &loop_on, sizeof loop_on);
    sockaddr_in self{};
    self.sin_family = AF_INET;
    socklen_t len = sizeof self;
    if (bind(rx, reinterpret_cast<sockaddr*>(&any), sizeof any) != 0 ||
        setsockopt(rx, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) != 0 ||
        bind(tx, reinterpret_cast<sockaddr*>(&self), sizeof self) != 0 ||
        getsockname(tx, reinterpret_cast<sockaddr*>(&self), &len) != 0)
      return;
    sockaddr_in group = any;
    group.sin_addr = mreq.imr_multiaddr;
    ++ready_;
    std::mt19937 rng(static_cast<unsigned>(17 + i));
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<char> buf(70000);
    while (!stop_) {
      pollfd p{rx, POLLIN, 0};
      if (poll(&p, 1, 10) > 0) {
        sockaddr_in from{};
        socklen_t flen = sizeof from;
        const ssize_t n = recvfrom(rx, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &flen);
        if (n > 0 && from.sin_port != self.sin_port) {  // not our own repeat
          for (std::size_t j = 0; j < ns_.size(); ++j) {
            if (j == i) continue;
            if (!link_up_(static_cast<int>(i), static_cast<int>(j)) || u(rng) < loss_) {
              ++dropped_;
              continue;
            }
            std::lock_guard<std::mutex> l(mu_);
            queues_[j].emplace_back(buf.begin(), buf.begin() + n);
          }
        }
      }
      std::deque<std::vector<char>> out;
      {
        std::lock_guard<std::mutex> l(mu_);
        out.swap(queues_[i]);
      }
      for (const auto& d : out) {
        sendto(tx, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&group), sizeof group);
        ++forwarded_;
      }
    }
    close(rx);
    close(tx);
  }
  std::vector<std::string> ns_;
  double loss_;
  std::function<bool(int, int)> link_up_;
  std::mutex mu_;
  std::vector<std::deque<std::vector<char>>> queues_;
  std::vector<std::thread> threads_;
  std::atomic<bool> stop_{false};
  std::atomic<int> ready_{0};
  std::atomic<std::uint64_t> forwarded_{0}, dropped_{0};
};

// Publishes to and listens on one robot's bus from inside that robot's namespace.
class Agent {
 public:
  Agent(const std::string& ns, int id) : thread_([this, ns, id] { loop(ns, id); }) {}
  ~Agent() {
    stop_ = true;
    thread_.join();
  }
  void publish(const KeyPoseBundle& b) {
    std::lock_guard<std::mutex> l(mu_);
    queue_.push_back(b);
  }
  std::vector<std::pair<int, int>> got() {
    std::lock_guard<std::mutex> l(mu_);
    return got_;
  }
  bool ready() const { return ready_; }

 private:
  void loop(const std::string& ns, int id) {
    if (!enterNetns(ns)) return;
    RobotBus bus(robotUrl(id));
    ready_ = bus.good();
    while (!stop_) {
      std::deque<KeyPoseBundle> todo;
      {
        std::lock_guard<std::mutex> l(mu_);
        todo.swap(queue_);
      }
      for (const auto& b : todo) bus.publish(b);
      bus.poll();
      {
        std::lock_guard<std::mutex> l(mu_);
        got_ = bus.got();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  std::atomic<bool> stop_{false}, ready_{false};
  std::mutex mu_;
  std::deque<KeyPoseBundle> queue_;
  std::vector<std::pair<int, int>> got_;
  std::thread thread_;
};

}  // namespace

TEST(PeerSyncNetns, ThreeNamespacesLossCutsAndKill) {
  const char* self = "PeerSyncNetns.ThreeNamespacesLossCutsAndKill";
  if (!std::getenv("SLIDE_TEAM_NETNS")) {
    if (geteuid() != 0) GTEST_SKIP() << "needs root for network namespaces";
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    const pid_t pid = spawn({"unshare", "-n", "env", "SLIDE_TEAM_NETNS=1", exe, std::string("--gtest_filter=") + self});
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the run inside the namespaces failed (see above)";
    return;
  }
  const std::string tag = "slteam" + std::to_string(getpid());
  auto ns = [&](int id) { return tag + "r" + std::to_string(id); };
  struct Cleanup {
    std::function<void()> f;
    ~Cleanup() { f(); }
  } cleanup{[&] {
    for (int id : kTeam) sh("ip netns del " + ns(id) + " 2>/dev/null");
  }};
  // One namespace per robot, loopback only (multicast routed to lo).
  for (int id : kTeam) {
    ASSERT_EQ(sh("ip netns add " + ns(id)), 0);
    ASSERT_EQ(sh("ip netns exec " + ns(id) + " sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo'"), 0);
  }
  // Each robot's link down for 2 s of every 4 s (phases differ) until `healed`; 30% loss always.
  std::atomic<bool> healed{false};
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [t0] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  auto up = [&](int i) { return healed || std::fmod(elapsed() + 1.3 * i, 4.0) < 2.0; };
  LossyHub hub({ns(1), ns(2), ns(3)}, 0.3, [&](int i, int j) { return up(i) && up(j); });
  const fs::path dir = fs::temp_directory_path() / (tag + "_state");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cfg = writeTestConfig(dir.string(), kTeamUrl);
  std::map<int, pid_t> pids;
  auto start = [&](int id) {
    pids[id] = spawn({"ip", "netns", "exec", ns(id), daemonBinary(), "--config", cfg, "--robot", std::to_string(id),
                      "--robot-url", robotUrl(id), "--log-level", "debug"},
                    (dir / ("robot" + std::to_string(id) + ".log")).string());
  };
  for (int id : kTeam) start(id);
  std::vector<std::unique_ptr<Agent>> agents;
  for (int id : kTeam) agents.push_back(std::make_unique<Agent>(ns(id), id));
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // daemons subscribed
  for (auto& a : agents) ASSERT_TRUE(a->ready());

  ASSERT_EQ(hub.ready(), 3);
  // 40 bundles per robot at 5 Hz; robot 2's daemon killed with -9 at bundle 20, back at 25.
  const int n = 40;
  std::mt19937 rng(8);
  for (int s = 0; s < n; ++s) {
    if (s == 20) stop(pids[2], SIGKILL);
    if (s == 25) {
      start(2);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    // While robot 2's daemon is down its tracker output would be lost: hold it back.
    if (s == 25)
      for (int k = 20; k < 25; ++k) agents[1]->publish(randomBundle(rng, 2, k));
    for (int id : kTeam) {
      if (id == 2 && s >= 20 && s < 25) continue;
      agents[static_cast<std::size_t>(id - 1)]->publish(randomBundle(rng, id, s));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  // Links healed (loss stays); wait for everything.
  healed = true;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(40);
  auto complete = [&] {
    for (auto& a : agents)
      if (a->got().size() < 2u * n) return false;
    return true;
  };
  while (!complete() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::seconds(1));  // nothing more may arrive
  std::printf("done after %.1f s; hub repeated %llu datagrams, dropped %llu\n", elapsed(),
              static_cast<unsigned long long>(hub.forwarded()), static_cast<unsigned long long>(hub.dropped()));
  EXPECT_GT(hub.dropped(), hub.forwarded() / 5);  // the loss really happened
  for (std::size_t i = 0; i < kTeam.size(); ++i)
    EXPECT_TRUE(deliveredExactlyOnceInOrder(agents[i]->got(), kTeam[i], kTeam, n));
  for (auto& [id, pid] : pids) stop(pid, SIGTERM);
  agents.clear();
  if (!HasFailure()) fs::remove_all(dir);
  else std::printf("daemon logs kept in %s\n", dir.c_str());
}
