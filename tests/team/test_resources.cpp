// Bounded resources on the team bus (issue 16, finding 8): the reassembly space counts the part
// slots a chunk header makes it allocate, not only payload bytes, and no sender takes it all.
#include <gtest/gtest.h>

#include "team/reassembly.h"

using namespace slide::team;

TEST(Reassembly, SpaceCountsAllocatedPartsAndIsShared) {
  const std::size_t cap = 4 << 20;
  Reassembler r(cap, 30000000);
  std::size_t refused = 0;
  // 870 chunks of 100 bytes, each the first of a payload claiming 32,767 parts (~0.8 MB of slots).
  for (int k = 0; k < 870; ++k) {
    Chunk c;
    c.origin = 1;
    c.seq = k;
    c.num_chunks = 32767;
    c.chunk_index = 0;
    c.data.assign(100, 7);
    std::optional<Drop> drop;
    EXPECT_FALSE(r.add(c, 0, &drop));
    if (drop == Drop::Overflow) ++refused;
    EXPECT_LE(r.bytes(), cap);
  }
  EXPECT_GE(refused, 860u);
  // Sender 0 holds at most half the space: another sender's map still fits.
  EXPECT_LE(r.bytes(), cap / 2);
  Chunk other;
  other.sender = 5;
  other.kind = ChunkKind::Map;
  other.origin = 5;
  other.num_chunks = 2;
  other.data.assign(500, 1);
  std::optional<Drop> other_drop;
  r.add(other, 0, &other_drop);
  EXPECT_FALSE(other_drop);
  // Expired partials give their space back; a real multi-chunk payload goes through.
  r.expire(60000000);
  EXPECT_EQ(r.bytes(), 0u);  // (the other sender's partial too)
  Bytes whole;
  for (int i = 0; i < 3; ++i) {
    Chunk c;
    c.kind = ChunkKind::Map;
    c.origin = 2;
    c.seq = 1;
    c.num_chunks = 3;
    c.chunk_index = static_cast<std::int16_t>(i);
    c.data.assign(50, static_cast<std::uint8_t>(i));
    whole.insert(whole.end(), c.data.begin(), c.data.end());
    std::optional<Drop> drop;
    auto out = r.add(c, 61000000, &drop);
    EXPECT_FALSE(drop);
    if (i == 2) {
      ASSERT_TRUE(out);
      EXPECT_EQ(*out, whole);
    }
  }
  EXPECT_EQ(r.bytes(), 0u);
}
