// Full solves off the update path: with background_solves an update never waits for a running
// full solve, whose result later enters the estimate with the key poses added meanwhile
// carried along; the optimizer node's stop writes its outputs without waiting for a running
// solve; periodic writes appear once their period has passed.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>

#include "io/tum_trajectory.h"
#include "io/object_map_text.h"
#include "optimizer_node.h"
#include "graph_scenario/scenario.h"
#include "scenario_messages.h"

using namespace slide;

namespace {

// Holds every background solve at its start until released.
struct Gate {
  std::mutex m;
  std::condition_variable cv;
  bool open = false;
  int entered = 0;
  void pass() {
    std::unique_lock<std::mutex> lock(m);
    ++entered;
    cv.notify_all();
    cv.wait(lock, [this] { return open; });
  }
  void waitEntered(int n) {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return entered >= n; });
  }
  void release() {
    std::lock_guard<std::mutex> lock(m);
    open = true;
    cv.notify_all();
  }
};

backend::BackendConfig backgroundConfig() {
  backend::BackendConfig c;
  c.background_solves = true;
  c.full_every = 40;
  return c;
}

std::string tempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("slide_bg_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

int tumLines(const std::string& path) { return static_cast<int>(io::readTum(path).size()); }

void feedOwn(OptimizerNode& node, const std::vector<slide::testing::RawMessage>& msgs, int count) {
  int n = 0;
  for (const auto& m : msgs)
    if (m.channel == "KEYPOSE_BUNDLE" && n++ < count) node.handle(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()));
}

}  // namespace

TEST(BackgroundSolves, UpdatesGoOnWhileAFullSolveRunsAndItsResultIsTakenIn) {
  const graph_scenario::GraphScenario s = graph_scenario::makeUrbanScenario();
  const auto& bundles = s.robots[0].bundles;
  backend::Optimizer opt(backgroundConfig(), ClassTable::loadDefault(), 0);
  Gate gate;
  opt.setSolveHook([&gate] { gate.pass(); });
  std::size_t k = 0;
  while (!opt.solving() && k < bundles.size()) ASSERT_TRUE(opt.addBundle(bundles[k++]).accepted);
  ASSERT_TRUE(opt.solving()) << "no full solve started";
  gate.waitEntered(1);
  const std::size_t held_from = k;
  // The solve is held: updates still return, each with its local solve, none with a full one.
  for (; k < held_from + 30; ++k) {
    const backend::UpdateResult u = opt.addBundle(bundles[k]);
    EXPECT_TRUE(u.accepted);
    EXPECT_FALSE(u.full_solve);
    EXPECT_TRUE(opt.solving());
  }
  const std::vector<backend::TrajectoryPose> before = opt.trajectory(0);
  gate.release();
  backend::UpdateResult r;
  while (!opt.poll(&r)) std::this_thread::yield();
  EXPECT_TRUE(r.full_solve);
  // The key poses added while it ran moved rigidly with the last solved one.
  const std::vector<backend::TrajectoryPose> after = opt.trajectory(0);
  ASSERT_EQ(after.size(), before.size());
  const std::size_t last = held_from - 1;
  for (std::size_t i = held_from; i < after.size(); ++i) {
    const Pose rel_before = before[last].pose.inverse() * before[i].pose;
    const Pose rel_after = after[last].pose.inverse() * after[i].pose;
    EXPECT_LT((rel_before.translation() - rel_after.translation()).norm(), 1e-9) << "key pose " << i;
  }
  // The rest of the run, then the same final solve as without a worker: the same estimate
  // within the scenario's noise. Each later solve is taken in before the next bundle, so the
  // run does not depend on the machine's load (where a solve is taken in changes which
  // landmarks later detections join).
  for (; k < bundles.size(); ++k) {
    EXPECT_TRUE(opt.addBundle(bundles[k]).accepted);
    while (opt.solving() && !opt.poll(&r)) std::this_thread::yield();
  }
  opt.fullSolve();
  backend::Optimizer sync(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (const auto& b : bundles) sync.addBundle(b);
  sync.fullSolve();
  const auto ta = opt.trajectory(0), tb = sync.trajectory(0);
  ASSERT_EQ(ta.size(), tb.size());
  double worst = 0;
  for (std::size_t i = 0; i < ta.size(); ++i) worst = std::max(worst, (ta[i].pose.translation() - tb[i].pose.translation()).norm());
  EXPECT_LT(worst, 0.2);
  EXPECT_NEAR(opt.numLandmarks(), sync.numLandmarks(), 0.02 * sync.numLandmarks());
}

// A loop closure that arrives while a solve runs must not reach the per-key-pose solves before
// its error is spread along its loop: they would pull the newest key poses alone onto it and
// bend the trajectory there by the whole accumulated drift.
TEST(BackgroundSolves, ALoopClosureWaitingForASolveNeverBendsTheNewestKeyPoses) {
  const graph_scenario::GraphScenario s = graph_scenario::makeUrbanScenario();
  const graph_scenario::ScenarioRobot& robot = s.robots[0];
  const std::vector<graph_scenario::ScenarioLoopClosure> closures = graph_scenario::simulateLoopClosures(robot);
  ASSERT_FALSE(closures.empty());
  const graph_scenario::ScenarioLoopClosure& lc = closures.front();
  backend::Optimizer opt(backgroundConfig(), ClassTable::loadDefault(), 0);
  Gate gate;
  opt.setSolveHook([&gate] { gate.pass(); });
  int k = 0;
  for (; k <= lc.seq_b; ++k) {
    ASSERT_TRUE(opt.addBundle(robot.bundles[k]).accepted);
    if (opt.solving()) gate.release();  // earlier solves run freely ...
    backend::UpdateResult ignored;
    while (opt.solving() && !opt.poll(&ignored)) std::this_thread::yield();
  }
  // The closure says the estimate misses the loop by 1 m sideways (as drift would; well inside
  // the odometry envelope).
  const Pose gap_before = opt.trajectory(0)[lc.seq_a].pose.inverse() * opt.trajectory(0)[lc.seq_b].pose;
  const Pose T_a_b = gap_before * poseFromXyzYaw(0.0, 1.0, 0.0, 0.0);
  const double miss = 1.0;
  Gate held;  // ... the next one is held while the loop closure arrives with its newer end the newest key pose
  opt.setSolveHook([&held] { held.pass(); });
  opt.settle();
  ASSERT_TRUE(opt.solving());
  held.waitEntered(1);
  ASSERT_TRUE(opt.addLoopClosure(0, lc.seq_a, lc.seq_b, T_a_b).accepted);
  ASSERT_LE(k + 5, static_cast<int>(robot.bundles.size()));
  for (const int until = k + 5; k < until; ++k) ASSERT_TRUE(opt.addBundle(robot.bundles[k]).accepted);
  const std::vector<backend::TrajectoryPose> live = opt.trajectory(0);
  for (int i = lc.seq_b - 2; i < k; ++i) {
    const Pose est = live[i - 1].pose.inverse() * live[i].pose;
    const Pose odom = robot.bundles[i - 1].odom_pose.inverse() * robot.bundles[i].odom_pose;
    EXPECT_LT((est.translation() - odom.translation()).norm(), 0.2) << "key pose " << i << " bent away from its odometry";
  }
  held.release();
  // The held solve (brought no closure: cancelled by it, or taken in) and then the one that
  // takes the loop closure in, spread along its loop.
  backend::UpdateResult r;
  for (int taken = 0; taken == 0 || opt.solving();) {
    if (opt.poll(&r)) ++taken;
    else std::this_thread::yield();
  }
  const std::vector<backend::TrajectoryPose> after = opt.trajectory(0);
  const Pose gap_after = after[lc.seq_a].pose.inverse() * after[lc.seq_b].pose;
  EXPECT_LT((gap_after.translation() - T_a_b.translation()).norm(), 0.8 * miss) << "the loop closure never came in";
}

TEST(BackgroundSolves, StopWritesTheOutputsWithoutWaitingForARunningSolve) {
  const auto msgs = slide::testing::twoRobotMessages();
  OptimizerNode node(backgroundConfig(), ClassTable::loadDefault(), 0, {}, {});
  const std::string dir = tempDir("stop");
  node.setOutputs(dir, 0);
  Gate gate;
  node.optimizer().setSolveHook([&gate] { gate.pass(); });
  feedOwn(node, msgs, 60);
  ASSERT_TRUE(node.optimizer().solving());
  gate.waitEntered(1);
  node.stop(0.5);  // returns while the solve is still held at its start
  EXPECT_EQ(tumLines(dir + "/trajectory_robot0.txt"), 60);
  const ObjectMap map =
      io::readObjectMapText(dir + "/map_robot0.txt", ClassTable::loadDefault(), io::MissingSize::Zero).map;
  EXPECT_EQ(static_cast<int>(map.size()), node.optimizer().numLandmarks());
  EXPECT_GT(map.size(), 10u);
  gate.release();  // the cancelled solve ends; its result is never taken in
  EXPECT_FALSE(node.optimizer().poll());
  std::filesystem::remove_all(dir);
}

TEST(BackgroundSolves, OutputsAreWrittenOncePerPeriodWhenTheEstimateChanged) {
  const auto msgs = slide::testing::twoRobotMessages();
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {}, {});
  const std::string dir = tempDir("periodic");
  const auto t0 = std::chrono::steady_clock::now();
  node.setOutputs(dir, 1.0);
  const std::string tum = dir + "/trajectory_robot0.txt";
  feedOwn(node, msgs, 20);
  node.poll(t0 + std::chrono::milliseconds(500));
  EXPECT_FALSE(std::filesystem::exists(tum)) << "written before its period";
  node.poll(t0 + std::chrono::milliseconds(1100));
  ASSERT_TRUE(std::filesystem::exists(tum));
  EXPECT_EQ(tumLines(tum), 20);
  EXPECT_TRUE(std::filesystem::exists(dir + "/map_robot0.txt"));
  EXPECT_FALSE(std::filesystem::exists(tum + ".tmp"));
  feedOwn(node, msgs, 30);  // the first 20 again (rejected as duplicates), then 10 new ones
  node.poll(t0 + std::chrono::milliseconds(1600));
  EXPECT_EQ(tumLines(tum), 20) << "written again before a period had passed";
  node.poll(t0 + std::chrono::milliseconds(2200));
  EXPECT_EQ(tumLines(tum), 30);
  std::filesystem::remove_all(dir);
}
