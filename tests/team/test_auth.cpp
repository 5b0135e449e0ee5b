#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "team/message_auth.h"
#include "team/team_keys.h"

using namespace slide::team;

TEST(MessageAuth, EveryFieldIsCoveredAndKeysMatter) {
  const std::vector<std::int32_t> team = {1, 2, 3};
  const MessageAuth auth(1, team, derivePairKeys("key-A", 1, team)), other(1, team, derivePairKeys("key-B", 1, team));
  // Robot 2 checks what robot 1 signs (with its own keys, derived from the same master).
  const MessageAuth two(2, team, derivePairKeys("key-A", 2, team)), two_other(2, team, derivePairKeys("key-B", 2, team));
  Chunk c;
  c.sender = 1;
  c.receiver = 2;
  c.counter = 77;
  c.origin = 3;
  c.seq = 4;
  c.chunk_index = 0;
  c.num_chunks = 2;
  c.data = {1, 2, 3, 4};
  auth.sign(c);
  EXPECT_EQ(c.mac.size(), 16u);  // two tags of 8 bytes: as many bytes as the one 16-byte MAC before
  EXPECT_TRUE(two.verify(c));
  EXPECT_FALSE(two_other.verify(c));
  EXPECT_FALSE(auth.verify(c));  // never its own
  std::vector<std::function<void(Chunk&)>> tamper = {
      [](Chunk& m) { m.sender = 9; },      [](Chunk& m) { m.receiver = -1; },
      [](Chunk& m) { m.counter++; },       [](Chunk& m) { m.kind = ChunkKind::Map; },
      [](Chunk& m) { m.origin = 0; },      [](Chunk& m) { m.seq = 5; },
      [](Chunk& m) { m.chunk_index = 1; }, [](Chunk& m) { m.num_chunks = 3; },
      [](Chunk& m) { m.data[2] ^= 1; },    [](Chunk& m) { m.data.pop_back(); },
      [](Chunk& m) { m.mac[5] ^= 0x10; }};
  for (std::size_t i = 0; i < tamper.size(); ++i) {
    Chunk t = c;
    tamper[i](t);
    EXPECT_FALSE(two.verify(t)) << "tamper " << i;
  }
  Heartbeat h;
  h.sender = 1;
  h.counter = 5;
  h.held[1].insert(SeqRange{0, 10});
  auth.sign(h);
  EXPECT_TRUE(two.verify(h));
  h.held[1].insert(11);
  EXPECT_FALSE(two.verify(h));
  Ack a;
  a.sender = 1;
  a.receiver = 2;
  a.acked[0].insert(3);
  auth.sign(a);
  EXPECT_TRUE(two.verify(a));
  a.receiver = 3;
  EXPECT_FALSE(two.verify(a));
  EXPECT_THROW(MessageAuth(1, team, {{2, "k"}}), std::invalid_argument);  // no key for robot 3
}

TEST(MessageAuth, NoRobotCanSpeakForAnother) {
  const std::vector<std::int32_t> team = {1, 2, 3};
  const MessageAuth one(1, team, derivePairKeys("m", 1, team)), three(3, team, derivePairKeys("m", 3, team));
  // Robot 2 signs a heartbeat as if from robot 1 with every key it holds: pair {1,2} is the only
  // key of robot 1's it has, so robot 3 (pair {1,3}) refuses it.
  const PairKeys two = derivePairKeys("m", 2, team);
  const MessageAuth impostor(1, team, {{2, two.at(1)}, {3, two.at(3)}});
  Heartbeat h;
  h.sender = 1;
  h.counter = 9;
  impostor.sign(h);
  EXPECT_FALSE(three.verify(h));
  one.sign(h);
  EXPECT_TRUE(three.verify(h));
}

TEST(MessageAuth, BundleTagsHoldATagForEachMemberAskedAndForNoOther) {
  const std::vector<std::int32_t> team = {1, 2, 3, 4};
  auto authOf = [&](std::int32_t id) { return MessageAuth(id, team, derivePairKeys("m", id, team)); };
  const MessageAuth one = authOf(1), two = authOf(2), three = authOf(3), four = authOf(4);
  const Bytes data = {9, 8, 7, 6};
  const Bytes block = one.bundleTags(5, data, {3, 4});
  EXPECT_EQ(block.size(), 2 + 2 * MessageAuth::kTagBytes);
  EXPECT_TRUE(one.bundleTagged(1, block, 3));
  EXPECT_FALSE(one.bundleTagged(1, block, 2));
  EXPECT_TRUE(three.verifyBundle(1, 5, data, block));
  EXPECT_TRUE(four.verifyBundle(1, 5, data, block));
  EXPECT_FALSE(two.verifyBundle(1, 5, data, block));           // no tag for robot 2
  EXPECT_FALSE(three.verifyBundle(1, 6, data, block));         // another seq
  EXPECT_FALSE(three.verifyBundle(2, 5, data, block));         // another origin
  EXPECT_TRUE(one.bundleTags(5, data, {1}).empty());           // none for the origin itself
  EXPECT_TRUE(one.verifyBundle(1, 5, data, block));            // the origin checks its own tags
  Bytes flipped = block;
  flipped.back() ^= 1;
  EXPECT_FALSE(one.verifyBundle(1, 5, data, flipped));
  EXPECT_TRUE(three.verifyBundle(1, 5, data, flipped));        // robot 3's tag is intact
  EXPECT_FALSE(four.verifyBundle(1, 5, data, flipped));
  EXPECT_FALSE(three.verifyBundle(1, 5, data, Bytes(block.begin(), block.end() - 1)));  // truncated
}

TEST(TeamKeys, FilesRoundTripAndBadFilesAreNamed) {
  const std::string dir = ::testing::TempDir() + "/slide_keys_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/robot2.keys";
  const PairKeys keys = {{1, randomPairKey()}, {3, randomPairKey()}};
  writeTeamKeys(path, 2, keys);
  EXPECT_EQ(loadTeamKeys(path, 2), keys);
  try {
    loadTeamKeys(path, 3);
    ADD_FAILURE() << "another robot's file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::filesystem::permissions(path, std::filesystem::perms::others_read, std::filesystem::perm_options::add);
  EXPECT_THROW(loadTeamKeys(path, 2), std::runtime_error);  // readable by others
  std::ofstream(dir + "/bad.keys") << "robot 2\npeer 1 xyz\n";
  std::filesystem::permissions(dir + "/bad.keys", std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  EXPECT_THROW(loadTeamKeys(dir + "/bad.keys", 2), std::runtime_error);
  std::filesystem::remove_all(dir);
}
