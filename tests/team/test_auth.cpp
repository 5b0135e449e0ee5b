#include <gtest/gtest.h>

#include "team/message_auth.h"

using namespace slide::team;

TEST(MessageAuth, EveryFieldIsCoveredAndKeysMatter) {
  const MessageAuth auth("key-A"), other("key-B");
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
  EXPECT_TRUE(auth.verify(c));
  EXPECT_FALSE(other.verify(c));
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
    EXPECT_FALSE(auth.verify(t)) << "tamper " << i;
  }
  Heartbeat h;
  h.sender = 1;
  h.counter = 5;
  h.held[1].insert(SeqRange{0, 10});
  auth.sign(h);
  EXPECT_TRUE(auth.verify(h));
  h.held[1].insert(11);
  EXPECT_FALSE(auth.verify(h));
  Ack a;
  a.sender = 1;
  a.receiver = 2;
  a.acked[0].insert(3);
  auth.sign(a);
  EXPECT_TRUE(auth.verify(a));
  a.receiver = 3;
  EXPECT_FALSE(auth.verify(a));
  EXPECT_THROW(MessageAuth(""), std::invalid_argument);
}
