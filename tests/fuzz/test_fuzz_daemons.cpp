// Every daemon against hostile messages on every input channel, as processes in a private
// network namespace (unshare -n; nothing leaves this test). Seeded variants of valid
// messages (hostile lengths at random positions, flipped bytes, truncations, absurd values;
// the fingerprint kept so the generated decoder sees them) go to the 16 input channels of
// segmenter, tracker, optimizer, loop closer, peer sync and deputy. Then every daemon must
// still be running, serve good messages (optimizer: status after a good bundle; tracker: a
// key-pose bundle from good frames), have counted what it dropped, and stop cleanly on
// SIGTERM. Then the optimizer's and peer sync's journals and peer sync's counters.txt are
// damaged between restarts (a flipped byte, a cut, garbage appended, a wrong character): each
// daemon starts, replays exactly the intact records, takes new input after them and keeps
// serving. SLIDE_FUZZ_ROUNDS (compile definition) scales the volume: the default run is quick,
// the `scenario` labelled build (FuzzDaemonsLong) does ten times as much.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <thread>

#include "../deputy/netns.h"
#include "hostile_messages.h"
#include "slide/daemon_status_t.hpp"
#include "slide/optimizer_status_t.hpp"
#include "team/journal.h"

#ifndef SLIDE_FUZZ_ROUNDS
#define SLIDE_FUZZ_ROUNDS 1
#endif
#if SLIDE_FUZZ_ROUNDS > 1
#define SLIDE_FUZZ_SUITE FuzzDaemonsLong  // its own name, so ctest's labels keep the two apart
#else
#define SLIDE_FUZZ_SUITE FuzzDaemons
#endif

using namespace slide;
using namespace slide::fuzz;

namespace {

const std::string kRobotUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608";
const std::string kTeamUrl = "udpm://239.255.76.90:7690?ttl=0&recv_buf_size=8388608";

struct Daemon {
  std::string name, log;
  pid_t pid = -1;
  ~Daemon() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
  bool alive() {
    int status = 0;
    return pid > 0 && waitpid(pid, &status, WNOHANG) == 0;
  }
  int stop() {  // exit status, -1 when killed by a signal or not stopping within 20 s
    kill(pid, SIGTERM);
    int status = 0;
    for (int i = 0; i < 400; ++i) {
      if (waitpid(pid, &status, WNOHANG) == pid) {
        pid = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }
  std::string text() const {
    std::ifstream in(log);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

void start(Daemon& d, const std::string& exe, std::vector<std::string> args, const std::string& dir,
           const std::string& tag = "") {
  d.name = exe;
  d.log = dir + "/" + exe + tag + ".log";
  args.insert(args.begin(), std::string(SLIDE_BINARY_DIR) + "/bin/" + exe);
  d.pid = fork();
  if (d.pid == 0) {
    if (!std::freopen(d.log.c_str(), "w", stderr)) _exit(126);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
}

struct Probe {
  int statuses = 0, dropped_in_status = 0, bundles = 0;
  void onStatus(const lcm::ReceiveBuffer*, const std::string&, const optimizer_status_t* m) {
    ++statuses;
    dropped_in_status = std::max(dropped_in_status, m->dropped_messages);
  }
  void onBundle(const lcm::ReceiveBuffer*, const std::string&, const keypose_bundle_t*) { ++bundles; }
  // Daemons without a status of their own: the most each one said it dropped.
  std::map<std::string, std::int64_t> daemon_dropped;
  void onDaemonStatus(const lcm::ReceiveBuffer*, const std::string&, const daemon_status_t* m) {
    auto& d = daemon_dropped[m->daemon];
    d = std::max(d, m->dropped_messages);
  }
};

void pump(lcm::LCM& lcm, double seconds, const std::function<bool()>& done = [] { return false; }) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end && !done()) lcm.handleTimeout(20);
}

// Sends the hostile variants of `valid` on `channel`, paced so that the receivers' socket
// buffers keep up; returns how many were sent.
int sendHostile(lcm::LCM& bus, const std::string& channel, const Bytes& valid, Mutator& mut, int rounds) {
  std::vector<Bytes> v = mut.hostileLengths(valid, static_cast<std::size_t>(12 * rounds));
  for (int i = 0; i < 60 * rounds; ++i) v.push_back(mut.flipped(valid, 1 + i % 3));
  for (int i = 0; i < 15 * rounds; ++i) v.push_back(mut.truncated(valid));
  for (int i = 0; i < 30 * rounds; ++i) v.push_back(mut.absurd(valid));
  std::shuffle(v.begin(), v.end(), mut.rng);
  int sent = 0;
  for (const Bytes& b : v) {
    if (bus.publish(channel, b.data(), static_cast<unsigned>(b.size())) == 0) ++sent;
    if (sent % 40 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(4));
  }
  return sent;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One seeded damage to the file at `path`: a flipped byte, a cut, or garbage appended; in a
// text file (counters.txt) a flipped byte is a wrong printable character. Returns what it did.
std::string damage(const std::string& path, std::mt19937& rng, bool text) {
  std::string b = readAll(path);
  std::string what;
  switch (rng() % 3) {
    case 0:
      if (b.empty()) return "nothing (empty)";
      {
        const std::size_t at = rng() % b.size();
        b[at] = text ? static_cast<char>(33 + rng() % 94) : static_cast<char>(b[at] ^ (1 + rng() % 255));
        what = "byte " + std::to_string(at) + " changed";
      }
      break;
    case 1: {
      const std::size_t len = b.empty() ? 0 : rng() % b.size();
      b.resize(len);
      what = "cut at " + std::to_string(len);
      break;
    }
    default: {
      const std::size_t n = 1 + rng() % 64;
      for (std::size_t i = 0; i < n; ++i) b.push_back(text ? static_cast<char>(33 + rng() % 94) : static_cast<char>(rng()));
      what = std::to_string(n) + " bytes of garbage appended";
    }
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), static_cast<std::streamsize>(b.size()));
  return path + ": " + what;
}

bool waitFor(Daemon& d, const std::string& text, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end && d.alive()) {
    if (d.text().find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return d.text().find(text) != std::string::npos;
}

struct Heartbeats {
  int count = 0;
  void on(const lcm::ReceiveBuffer*, const std::string&) { ++count; }
};

}  // namespace

TEST(SLIDE_FUZZ_SUITE, DamagedJournalsAndStateFilesAreRecoveredAtRestartAndServingGoesOn) {
  const std::string why = slide::test::enterPrivateNetns();
  if (!why.empty()) GTEST_SKIP() << "no private network namespace: " << why;
  const std::string dir = std::filesystem::temp_directory_path() / ("slide_fuzz_state_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string keys_cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-team-keys --team 0,1,2 --out " + dir +
                               "/keys --log-level warn";
  ASSERT_EQ(std::system(keys_cmd.c_str()), 0) << keys_cmd;
  const std::string journal = dir + "/optimizer.journal", state = dir + "/peer_sync";
  lcm::LCM bus(kRobotUrl), team(kTeamUrl);
  ASSERT_TRUE(bus.good() && team.good());
  Probe probe;
  bus.subscribe("OPTIMIZER_STATUS", &Probe::onStatus, &probe);
  Heartbeats heartbeats;
  team.subscribe("TEAM_HEARTBEAT", &Heartbeats::on, &heartbeats);
  std::mt19937 rng(20261202);
  const int rounds = 3 * SLIDE_FUZZ_ROUNDS, per_round = 3;
  for (int r = 0; r <= rounds; ++r) {
    // Damage, then what each daemon must find intact (a read-only scan of the same format).
    std::string what;
    if (r > 0) {
      what = damage(journal, rng, false) + "; " + damage(state + "/journal.bin", rng, false);
      if (std::filesystem::exists(state + "/counters.txt")) what += "; " + damage(state + "/counters.txt", rng, true);
    }
    const std::size_t opt_intact = slide::team::Journal::read(journal).size();
    const std::size_t ps_intact = slide::team::Journal::read(state + "/journal.bin").size();
    SCOPED_TRACE("round " + std::to_string(r) + ": " + what);
    Daemon opt, ps;
    const std::string tag = "-" + std::to_string(r);
    start(opt, "slide-optimizer", {"--robot", "0", "--lcm-url", kRobotUrl, "--journal", journal, "--log-level", "info"},
          dir, tag);
    start(ps, "slide-peer-sync",
          {"--robot", "0", "--robot-url", kRobotUrl, "--team-url", kTeamUrl, "--state-dir", state, "--team-key-file",
           dir + "/keys/robot0.keys", "--log-level", "info"},
          dir, tag);
    heartbeats.count = 0;
    ASSERT_TRUE(waitFor(opt, "replayed " + std::to_string(opt_intact) + " inputs", 10))
        << "the optimizer did not replay its " << opt_intact << " intact records:\n" << opt.text();
    ASSERT_TRUE(waitFor(ps, "(" + std::to_string(ps_intact) + " records)", 10))
        << "peer sync did not keep its " << ps_intact << " intact records:\n" << ps.text();
    ASSERT_TRUE(waitFor(opt, "robot 0 optimizer on", 10)) << opt.text();  // subscribed
    pump(team, 3.0, [&] { return heartbeats.count > 0; });
    EXPECT_GT(heartbeats.count, 0) << "peer sync does not serve the team bus:\n" << ps.text();
    // New input goes in after the intact records (seqs beyond any held: lost ones are bridged).
    probe.statuses = 0;
    for (int k = 0; k < per_round; ++k) {
      const keypose_bundle_t b = bundle(0, 1000 * (r + 1) + k);
      bus.publish("KEYPOSE_BUNDLE", &b);
      pump(bus, 0.05);
    }
    pump(bus, 5.0, [&] { return probe.statuses >= per_round; });
    EXPECT_GE(probe.statuses, per_round) << "the optimizer does not answer:\n" << opt.text();
    for (Daemon* d : {&opt, &ps}) ASSERT_EQ(d->stop(), 0) << d->name << " did not stop cleanly:\n" << d->text();
    EXPECT_EQ(slide::team::Journal::read(journal).size(), opt_intact + per_round) << opt.text();
    EXPECT_GE(slide::team::Journal::read(state + "/journal.bin").size(), ps_intact + per_round) << ps.text();
  }
  std::printf("%d restarts after damaged journals and counters\n", rounds);
  std::filesystem::remove_all(dir);
}

TEST(SLIDE_FUZZ_SUITE, EveryDaemonSurvivesHostileMessagesOnEveryInputAndKeepsServing) {
  const std::string why = slide::test::enterPrivateNetns();
  if (!why.empty()) GTEST_SKIP() << "no private network namespace: " << why;
  const std::string dir = std::filesystem::temp_directory_path() / ("slide_fuzz_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);

  Daemon seg, trk, opt, lc, ps, dep;
  const std::vector<std::string> robot{"--robot", "0", "--lcm-url", kRobotUrl, "--log-level", "info"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = robot;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  start(seg, "slide-segmenter", robot, dir);
  start(trk, "slide-tracker", robot, dir);
  start(opt, "slide-optimizer", with({"--journal", dir + "/optimizer.journal"}), dir);
  start(lc, "slide-loop-closer", robot, dir);
  const std::string keys_cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-team-keys --team 0,1,2 --out " + dir +
                               "/keys --log-level warn";
  ASSERT_EQ(std::system(keys_cmd.c_str()), 0) << keys_cmd;
  start(ps, "slide-peer-sync",
        {"--robot", "0", "--robot-url", kRobotUrl, "--team-url", kTeamUrl, "--state-dir", dir + "/peer_sync",
         "--team-key-file", dir + "/keys/robot0.keys", "--log-level", "info"},
        dir);
  start(dep, "slide-deputy", {"--id", "fuzz-deputy", "--lcm-url", kRobotUrl, "--discovery-ms", "200"}, dir);
  std::vector<Daemon*> all{&seg, &trk, &opt, &lc, &ps, &dep};
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  for (Daemon* d : all) ASSERT_TRUE(d->alive()) << d->name << " did not start:\n" << d->text();

  lcm::LCM bus(kRobotUrl), team(kTeamUrl);
  ASSERT_TRUE(bus.good() && team.good());
  Probe probe;
  bus.subscribe("OPTIMIZER_STATUS", &Probe::onStatus, &probe);
  bus.subscribe("KEYPOSE_BUNDLE", &Probe::onBundle, &probe);
  bus.subscribe("DAEMON_STATUS", &Probe::onDaemonStatus, &probe);

  Mutator mut(20261201);
  const int rounds = SLIDE_FUZZ_ROUNDS;
  int sent = 0;
  const std::vector<std::tuple<lcm::LCM*, std::string, Bytes>> inputs{
      {&bus, "SCAN", encode(scan(0, 1))},
      {&bus, "RGBD", encode(rgbd(0, 1))},
      {&bus, "ODOM", encode(odometry(0, 1))},
      {&bus, "INSTANCES", encode(instances(0, 1))},
      {&bus, "KEYPOSE_BUNDLE", encode(bundle(0, 1))},
      {&bus, "PEER_BUNDLE", encode(bundle(1, 1))},
      {&bus, "LOOP_CLOSURE", encode(loopClosure(0))},
      {&bus, "OBJECT_MAP", encode(objectMap(0))},
      {&bus, "OWN_MAP", encode(objectMap(0))},
      {&bus, "PEER_MAP", encode(objectMap(1))},
      {&bus, "TRAJECTORY", encode(trajectory(0))},
      {&team, "TEAM_HEARTBEAT", encode(heartbeat(1))},
      {&team, "TEAM_CHUNK", encode(chunk(1))},
      {&team, "TEAM_ACK", encode(ack(1, 0))},
      {&bus, "PM_DISCOVER", encode(discovery())},
      {&bus, "PM_INFO", encode(deputyInfo("fuzz-other"))},
      {&bus, "PM_ORDERS", encode(orders("fuzz-other"))},
  };
  for (const auto& [out, channel, valid] : inputs) {
    sent += sendHostile(*out, channel, valid, mut, rounds);
    pump(bus, 0.05);
    for (Daemon* d : all) ASSERT_TRUE(d->alive()) << d->name << " died on hostile " << channel << ":\n" << d->text();
  }
  std::printf("sent %d hostile messages on %zu channels\n", sent, inputs.size());
  pump(bus, 2.0);
  for (Daemon* d : all) ASSERT_TRUE(d->alive()) << d->name << " died after the hostile phase:\n" << d->text();

  // Good messages are still served. The tracker: frames 1.5 m apart, far in the future of
  // anything hostile, must give key-pose bundles; the optimizer answers a good bundle.
  probe.bundles = 0;
  for (int i = 0; i < 8; ++i) {
    frame_instances_t f = instances(0, 1000000 + i);
    f.header.utime = 4000000000000000LL + i * 100000;
    f.odom_pose = pose(1.5 * i, 0);
    bus.publish("INSTANCES", &f);
    pump(bus, 0.1);
  }
  pump(bus, 2.0, [&] { return probe.bundles > 0; });
  EXPECT_GT(probe.bundles, 0) << "the tracker no longer turns good frames into bundles:\n" << trk.text();
  probe.statuses = 0;
  keypose_bundle_t good = bundle(0, 1999999999);
  good.header.utime = 4100000000000000LL;
  bus.publish("KEYPOSE_BUNDLE", &good);
  pump(bus, 5.0, [&] { return probe.statuses > 0; });
  EXPECT_GT(probe.statuses, 0) << "the optimizer no longer answers:\n" << opt.text();
  EXPECT_GT(probe.dropped_in_status, 0) << "the optimizer's status does not count what it dropped";

  for (Daemon* d : all) {
    ASSERT_TRUE(d->alive()) << d->name << " died:\n" << d->text();
    const std::string log_before = d->text();
    EXPECT_EQ(d->stop(), 0) << d->name << " did not stop cleanly:\n" << d->text();
    const std::string log = d->text();
    EXPECT_NE(log.find("dropped"), std::string::npos) << d->name << " counted no dropped message:\n" << log;
  }
  // The segmenter, tracker and loop closer say so on the bus too (their last status at stop).
  pump(bus, 0.5);
  for (const char* name : {"segmenter", "tracker", "loop_closer"})
    EXPECT_GT(probe.daemon_dropped[name], 0) << name << " published no count of its dropped messages";
  std::filesystem::remove_all(dir);
}
