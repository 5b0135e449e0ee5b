// The optimizer against absurd closures and transforms and a full disk (issue 16 finding 5):
// a loop closure far from what odometry allows (5 km / 3 rad, 1e300) and a peer transform of
// 1e300 are rejected before they touch the graph or the journal; a true closure still goes
// in; a journal on a full disk is an alarm in the status message, not silence.
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>

#include "../backend/scenario_messages.h"
#include "backend/optimizer.h"
#include "optimizer_node.h"
#include "slide/optimizer_status_t.hpp"

using namespace slide;

TEST(HostileOptimizer, AbsurdLoopClosuresAndTransformsAreRejectedAndTrueOnesAccepted) {
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(1);
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  const auto& truth = s.robots[0].truth;
  for (int i = 0; i < 40; ++i) ASSERT_TRUE(opt.addBundle(s.robots[0].bundles[i]).accepted);
  const int a = s.robots[0].bundles[5].seq, b = s.robots[0].bundles[35].seq;
  const Pose T_true = truth[5].inverse() * truth[35];
  Pose far = T_true;
  far.translation() += Eigen::Vector3d(5000, 0, 0);
  Pose turned = T_true;
  turned.linear() = turned.linear() * Eigen::AngleAxisd(3.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Pose huge = Pose::Identity();
  huge.translation() = Eigen::Vector3d(1e300, 0, 0);
  for (const Pose& bad : {far, turned, huge}) {
    const backend::UpdateResult r = opt.addLoopClosure(0, a, b, bad);
    EXPECT_FALSE(r.accepted);
    EXPECT_NE(r.reason.find("implausible loop closure"), std::string::npos) << r.reason;
  }
  const double cost_before = opt.cost();
  EXPECT_TRUE(std::isfinite(cost_before));
  const backend::UpdateResult good = opt.addLoopClosure(0, a, b, T_true);
  EXPECT_TRUE(good.accepted) << good.reason;
  EXPECT_TRUE(std::isfinite(opt.cost()));
  const backend::UpdateResult t = opt.addRobotTransform(1, huge);
  EXPECT_FALSE(t.accepted);
  EXPECT_NE(t.reason.find("absurd transform"), std::string::npos) << t.reason;
  for (const auto& lm : opt.landmarks()) ASSERT_TRUE(lm.isFinite());
}

TEST(HostileOptimizer, AJournalOnAFullDiskIsAnAlarmInTheStatus) {
  // A full disk of our own: a 64 KB tmpfs in a private mount namespace, filled up.
  const std::string dir = std::filesystem::temp_directory_path() / ("slide_full_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  if (geteuid() != 0 || unshare(CLONE_NEWNS) != 0 || mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
      mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs (needs root)";
  {
    std::ofstream fill(dir + "/fill", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && fill; ++i) fill << block << std::flush;
  }
  std::vector<optimizer_status_t> statuses;
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, OptimizerChannels{},
                     [&](const std::string& channel, const std::vector<uint8_t>& bytes) {
                       optimizer_status_t st;
                       if (channel == "OPTIMIZER_STATUS" &&
                           st.decode(bytes.data(), 0, static_cast<int>(bytes.size())) == static_cast<int>(bytes.size()))
                         statuses.push_back(st);
                       return true;
                     });
  node.openJournal(dir + "/optimizer.journal");  // every write fails with ENOSPC
  const auto msgs = slide::testing::twoRobotMessages();
  int fed = 0;
  for (const auto& m : msgs) {
    if (m.channel != "KEYPOSE_BUNDLE") continue;
    EXPECT_NO_THROW(node.handle(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size())));
    if (++fed == 5) break;
  }
  ASSERT_FALSE(statuses.empty());
  // A status goes out before its input is journalled: the last one counts the first four.
  EXPECT_EQ(statuses.back().unjournalled_inputs, 4);
  EXPECT_EQ(node.unjournalled(), 5);
  EXPECT_EQ(statuses.back().num_keyposes, 5);  // still serving
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);  // the mount goes with the namespace
}
