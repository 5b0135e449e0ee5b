// Peer sync's state files against an unlucky disk (issue 16, findings 5 and 6): a full disk
// while journalling bundles, deliveries and counters is counted (an alarm), never fatal, and
// syncing goes on once space returns; a damaged counters.txt (one bad character) does not stop
// the robot: the bad line is skipped with a warning and the robot is heard after a restart. A
// damaged journal tail on a full disk is cut without its saved copy.
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "team/journal.h"
#include "team/sim_network.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;
namespace fs = std::filesystem;

namespace {

constexpr Micros kSecond = 1000000;
const std::vector<std::int32_t> kIds = {3, 7, 11};

std::vector<SyncConfig> configs() {
  std::vector<SyncConfig> cfgs;
  for (auto id : kIds) cfgs.push_back(teamConfig(id, kIds));
  return cfgs;
}

std::string freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("slide_team_disk_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::set<std::int32_t> deliveredFrom(const SimNetwork& net, std::size_t at, std::int32_t origin) {
  std::set<std::int32_t> out;
  for (const auto& [o, s] : net.delivered(at))
    if (o == origin) out.insert(s);
  return out;
}

}  // namespace

TEST(PeerSyncFullDisk, WritesThatFailAreCountedNotFatalAndSyncGoesOnWhenSpaceReturns) {
  // A full disk of our own: a small tmpfs in a private mount namespace.
  const std::string dir = freshDir("full");
  if (geteuid() != 0 || unshare(CLONE_NEWNS) != 0 || mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
      mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=1m") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs (needs root)";
  std::mt19937 rng(3);
  {
    SimNetwork net(configs(), dir + "/state", SimLinkModel{}, 1);
    for (int s = 0; s < 5; ++s) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now()));
    net.run(10 * kSecond);
    ASSERT_EQ(deliveredFrom(net, 1, kIds[0]).size(), 5u);
    // Robot 7's bundles are journalled before the disk fills; its peers get them after.
    for (int s = 0; s < 5; ++s) ASSERT_FALSE(net.node(1).addOwnBundle(randomBundle(rng, kIds[1], s), net.now()));
    {
      std::ofstream fill(dir + "/fill", std::ios::binary);
      const std::string block(4096, 'x');
      while (fill << block << std::flush) {
      }
    }
    // Every robot's journal and counters.txt now fail (once the last page of each file is
    // used up): own bundles, peers' bundles, deliveries and counters alike. Nothing throws;
    // own bundles are refused and counted.
    std::set<std::int32_t> taken{0, 1, 2, 3, 4};
    int refused = 0;
    for (int s = 5; s < 40; ++s) {
      const auto drop = net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now());
      if (!drop) taken.insert(s);
      else {
        EXPECT_EQ(*drop, Drop::JournalWrite);
        ++refused;
      }
    }
    EXPECT_GT(refused, 20);
    EXPECT_NO_THROW(net.run(10 * kSecond));
    for (std::size_t i = 0; i < 3; ++i) EXPECT_GT(net.node(i).stateWriteFailures(), 0u) << "robot " << kIds[i];
    EXPECT_GE(net.node(0).dropped(Drop::JournalWrite), static_cast<std::uint64_t>(refused));
    EXPECT_GT(net.node(2).dropped(Drop::JournalWrite), 0u);  // robot 7's bundles: sent again later
    EXPECT_GT(net.node(2).db().journalFailures(), 0u);
    // Space returns: what was refused comes again, the gap of lost own bundles is bridged.
    fs::remove(dir + "/fill");
    for (int s = 40; s < 42; ++s) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now()));
    taken.insert({40, 41});
    net.run(30 * kSecond);
    EXPECT_EQ(deliveredFrom(net, 1, kIds[0]), taken);
    EXPECT_EQ(deliveredFrom(net, 2, kIds[1]), (std::set<std::int32_t>{0, 1, 2, 3, 4}));
    // After a restart of everyone, the journals hold what was taken and sync goes on.
    for (std::size_t i = 0; i < 3; ++i) net.restart(i);
    for (int s = 42; s < 44; ++s) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now()));
    net.run(30 * kSecond);
    EXPECT_TRUE(deliveredFrom(net, 2, kIds[0]).count(43));
  }
  umount(dir.c_str());
  fs::remove_all(dir);
}

TEST(PeerSyncFullDisk, AJournalWithADamagedTailOpensOnAFullDiskAndTheTailIsCutUnsaved) {
  const std::string dir = freshDir("tail");
  if (geteuid() != 0 || unshare(CLONE_NEWNS) != 0 || mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
      mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs (needs root)";
  const std::string path = dir + "/journal.bin";
  {
    Journal j(path, nullptr);
    for (int i = 0; i < 3; ++i) j.append(1, Bytes(100, static_cast<std::uint8_t>(i)));
  }
  const auto good = fs::file_size(path);
  std::ofstream(path, std::ios::app | std::ios::binary) << std::string(5000, 'x');  // a torn tail
  {
    std::ofstream fill(dir + "/fill", std::ios::binary);
    const std::string block(4096, 'x');
    while (fill << block << std::flush) {
    }
  }
  std::vector<JournalRecord> records;
  JournalRecovery info;
  ASSERT_NO_THROW(Journal(path, &records, &info));
  EXPECT_EQ(records.size(), 3u);
  EXPECT_EQ(fs::file_size(path), good);
  EXPECT_NE(info.not_saved.find("cannot save it to " + path + ".damaged-"), std::string::npos) << info.not_saved;
  EXPECT_TRUE(info.damaged_copy.empty());
  umount(dir.c_str());
  fs::remove_all(dir);
}

TEST(PeerSyncFullDisk, ADamagedCountersFileIsSkippedLineByLineWithAWarning) {
  const std::string dir = freshDir("counters");
  const std::string path = dir + "/counters.txt";
  std::ofstream(path) << "own 1767225600000000\nsender 7 17672256x0000000\nsender 11 1767225600000123\n";
  const WallClock clock = [] { return SimNetwork::kSimEpoch + 5 * kSecond; };
  CounterStore c(path, clock);
  ASSERT_EQ(c.warnings().size(), 1u);
  EXPECT_NE(c.warnings()[0].find(path + ":2: skipped malformed counter line"), std::string::npos) << c.warnings()[0];
  EXPECT_EQ(c.lastAccepted(11), 1767225600000123);
  EXPECT_EQ(c.lastAccepted(7), -1);  // as if counters.txt were lost for robot 7
  EXPECT_GE(c.nextOwn(), clock());
  // The own line damaged: the robot goes on from the clock.
  std::ofstream(path, std::ios::trunc) << "own 1767225600O00000\n";
  CounterStore d(path, clock);
  EXPECT_EQ(d.warnings().size(), 1u);
  EXPECT_EQ(d.nextOwn(), clock());
  fs::remove_all(dir);
}

TEST(PeerSyncFullDisk, APeerSyncWithADamagedCountersFileStartsAndIsHeard) {
  const std::string dir = freshDir("restart");
  std::mt19937 rng(4);
  {
    SimNetwork net(configs(), dir, SimLinkModel{}, 2);
    for (int s = 0; s < 3; ++s) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now()));
    net.run(10 * kSecond);
    for (std::size_t i = 0; i < 3; ++i) net.node(i).persist();
    // One bad character in every line of robot 3's counters.txt.
    const std::string path = dir + "/robot3/counters.txt";
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), damaged;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) damaged += line.substr(0, line.size() - 2) + "#" + line.back() + "\n";
    std::ofstream(path, std::ios::trunc) << damaged;
    ASSERT_NO_THROW(net.restart(0));
    EXPECT_EQ(net.node(0).counters().warnings().size(), 3u);  // own and two senders
    for (int s = 3; s < 6; ++s) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, kIds[0], s), net.now()));
    net.run(10 * kSecond);
    for (std::size_t i : {1u, 2u}) EXPECT_EQ(deliveredFrom(net, i, kIds[0]).size(), 6u) << "robot " << kIds[i];
  }
  fs::remove_all(dir);
}
