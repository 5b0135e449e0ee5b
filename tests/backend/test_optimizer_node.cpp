// The optimizer node: a restart from the journal ends with the same map and trajectories as
// an uninterrupted run; rejected and undecodable inputs are counted, not journaled.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "optimizer_node.h"
#include "scenario_messages.h"

using namespace slide;
using slide::testing::RawMessage;

namespace {

std::string tempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("slide_backend_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::filesystem::remove(p);
  return p.string();
}

void feed(OptimizerNode& node, const std::vector<RawMessage>& msgs, std::size_t from, std::size_t to) {
  for (std::size_t i = from; i < to; ++i)
    node.handle(msgs[i].channel, msgs[i].bytes.data(), static_cast<int>(msgs[i].bytes.size()));
}

int journalEvents(const std::string& path) { return static_cast<int>(OptimizerNode::readJournal(path).size()); }

}  // namespace

TEST(OptimizerNode, RestartFromJournalGivesTheSameMap) {
  const std::vector<RawMessage> msgs = slide::testing::twoRobotMessages();
  const ClassTable classes = ClassTable::loadDefault();
  OptimizerNode clean(backend::BackendConfig{}, classes, 0, {}, {});
  feed(clean, msgs, 0, msgs.size());

  const std::string journal = tempPath("optimizer.journal");
  const std::size_t cut = msgs.size() * 3 / 5;  // after the merge, before the loop closure
  {
    OptimizerNode first(backend::BackendConfig{}, classes, 0, {}, {});
    EXPECT_EQ(first.openJournal(journal), 0);
    feed(first, msgs, 0, cut);
    // A duplicate is rejected and stays out of the journal.
    feed(first, msgs, 0, 1);
    EXPECT_EQ(first.optimizer().rejected(), 1);
  }  // killed here; every accepted input is already flushed to the journal
  EXPECT_EQ(journalEvents(journal), static_cast<int>(cut));

  OptimizerNode second(backend::BackendConfig{}, classes, 0, {}, {});
  EXPECT_EQ(second.openJournal(journal), static_cast<int>(cut));
  feed(second, msgs, cut, msgs.size());
  EXPECT_EQ(journalEvents(journal), static_cast<int>(msgs.size()));

  const backend::Optimizer& a = clean.optimizer();
  const backend::Optimizer& b = second.optimizer();
  EXPECT_EQ(b.robots(), (std::vector<int>{0, 1}));
  EXPECT_EQ(a.numKeyPoses(), b.numKeyPoses());
  const auto la = a.landmarks(), lb = b.landmarks();
  ASSERT_EQ(la.size(), lb.size());
  ASSERT_GT(la.size(), 20u);
  for (std::size_t i = 0; i < la.size(); ++i) {
    EXPECT_EQ(la[i].id, lb[i].id);
    EXPECT_LT((la[i].position() - lb[i].position()).norm(), 1e-9);
  }
  for (int r : {0, 1}) {
    const auto ta = a.trajectory(r), tb = b.trajectory(r);
    ASSERT_EQ(ta.size(), tb.size());
    for (std::size_t i = 0; i < ta.size(); ++i)
      EXPECT_LT((ta[i].pose.translation() - tb[i].pose.translation()).norm(), 1e-9);
  }
  std::filesystem::remove_all(std::filesystem::path(journal).parent_path());
}

TEST(OptimizerNode, CountsUndecodableAndMisroutedInput) {
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {}, {});
  const std::vector<uint8_t> junk = {1, 2, 3, 4, 5};
  node.handle("KEYPOSE_BUNDLE", junk.data(), static_cast<int>(junk.size()));
  node.handle("LOOP_CLOSURE", junk.data(), static_cast<int>(junk.size()));
  EXPECT_EQ(node.decodeErrors(), 2);
  // A peer's bundle on the own channel is ignored.
  const auto msgs = slide::testing::twoRobotMessages();
  node.handle("KEYPOSE_BUNDLE", msgs[1].bytes.data(), static_cast<int>(msgs[1].bytes.size()));
  EXPECT_EQ(node.optimizer().numKeyPoses(), 0);
  node.handle("OTHER", msgs[0].bytes.data(), static_cast<int>(msgs[0].bytes.size()));
  EXPECT_EQ(node.optimizer().numKeyPoses(), 0);
}

TEST(OptimizerNode, SettlesTheEstimateOnceWhenInputsStop) {
  // Update-path full solves run one or two iterations; once the inputs stop, poll() solves the
  // estimate to convergence once (and publishes it), and does not again until inputs change it.
  const std::vector<RawMessage> msgs = slide::testing::twoRobotMessages();
  int maps = 0;
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {},
                     [&](const std::string& channel, const std::vector<uint8_t>&) {
                       maps += channel == "OBJECT_MAP";
                       return true;
                     });
  node.setSettle(2.0);
  feed(node, msgs, 0, msgs.size());
  const auto t = std::chrono::steady_clock::now();
  const std::vector<backend::TrajectoryPose> before = node.optimizer().trajectory(0);
  const int maps_before = maps;
  node.poll(t);  // inputs just came: nothing yet
  EXPECT_EQ(maps, maps_before);
  node.poll(t + std::chrono::seconds(3));
  EXPECT_EQ(maps, maps_before + 1) << "the settled estimate is published";
  const std::vector<backend::TrajectoryPose> after = node.optimizer().trajectory(0);
  ASSERT_EQ(after.size(), before.size());
  double moved = 0;
  for (std::size_t i = 0; i < after.size(); ++i)
    moved = std::max(moved, (after[i].pose.translation() - before[i].pose.translation()).norm());
  EXPECT_GT(moved, 1e-6) << "the settling solve changed nothing: the estimate was already converged";
  node.poll(t + std::chrono::seconds(6));
  EXPECT_EQ(maps, maps_before + 1) << "settled twice without new input";
}
