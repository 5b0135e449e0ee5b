// LCM mapping of the team messages: round trips, sizes used for accounting, bad input.
#include <gtest/gtest.h>

#include "team/message_auth.h"
#include "team_test_util.h"
#include "../../daemons/peer_sync/team_msg.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;

TEST(TeamMsg, RoundTripsKeepTheMacValidAndSizesMatchLcm) {
  const std::vector<std::int32_t> team = {1, 2, 3};
  const MessageAuth two = authOf(2, team, "k"), three = authOf(3, team, "k"), one = authOf(1, team, "k");
  Heartbeat h;
  h.sender = 2;
  h.counter = 99;
  h.held[1].insert(SeqRange{0, 10});
  h.held[1].insert(SeqRange{20, 30});
  h.held[3].insert(5);
  h.maps = {{1, 1700}, {3, 12}};
  two.sign(h);
  const sync_heartbeat_t lh = toLcm(h);
  EXPECT_EQ(static_cast<std::size_t>(lh.getEncodedSize()), encodedSize(h));
  std::string why;
  auto h2 = fromLcm(lh, &why);
  ASSERT_TRUE(h2) << why;
  EXPECT_TRUE(one.verify(*h2));
  EXPECT_EQ(h2->maps, h.maps);
  Heartbeat forged = *h2;
  forged.maps[1] = 1701;  // the map versions are under the MAC too
  EXPECT_FALSE(one.verify(forged));

  Chunk c;
  c.sender = 2;
  c.receiver = -1;
  c.counter = 100;
  c.origin = 1;
  c.seq = 4;
  c.data = {1, 2, 3, 4, 5};
  two.sign(c);
  const sync_chunk_t lc = toLcm(c);
  EXPECT_EQ(static_cast<std::size_t>(lc.getEncodedSize()), encodedSize(c));
  auto c2 = fromLcm(lc, &why);
  ASSERT_TRUE(c2) << why;
  EXPECT_TRUE(one.verify(*c2));

  Ack a;
  a.sender = 3;
  a.receiver = 2;
  a.counter = 5;
  a.acked[1].insert(SeqRange{0, 3});
  three.sign(a);
  const sync_ack_t la = toLcm(a);
  EXPECT_EQ(static_cast<std::size_t>(la.getEncodedSize()), encodedSize(a));
  auto a2 = fromLcm(la, &why);
  ASSERT_TRUE(a2) << why;
  EXPECT_TRUE(one.verify(*a2));
}

TEST(TeamMsg, MalformedInputIsRefusedWithAReason) {
  sync_heartbeat_t h{};
  h.num_origins = 1;
  h.held.resize(1);
  h.held[0].origin = 1;
  h.held[0].num_ranges = 2;
  h.held[0].ranges.resize(2);
  h.held[0].ranges[0].first = 5;
  h.held[0].ranges[0].last = 9;
  h.held[0].ranges[1].first = 7;  // overlaps
  h.held[0].ranges[1].last = 12;
  std::string why;
  EXPECT_FALSE(fromLcm(h, &why));
  EXPECT_NE(why.find("overlap"), std::string::npos);
  h.held[0].ranges[1].first = 3;
  h.held[0].ranges[1].last = 2;
  EXPECT_FALSE(fromLcm(h, &why));
  h.held[0].ranges[1].first = 11;  // valid again
  h.held[0].ranges[1].last = 12;
  map_version_t twice;
  twice.origin = 3;
  twice.version = 5;
  h.maps = {twice, twice};
  h.num_maps = 2;
  EXPECT_FALSE(fromLcm(h, &why));
  EXPECT_NE(why.find("listed twice"), std::string::npos);
  h.maps.resize(1);
  h.maps[0].version = 0;
  h.num_maps = 1;
  EXPECT_FALSE(fromLcm(h, &why));
  h.maps[0].version = 5;
  EXPECT_TRUE(fromLcm(h, &why)) << why;
  sync_chunk_t c{};
  c.kind = 7;
  EXPECT_FALSE(fromLcm(c, &why));
  // Truncated or trailing bytes never decode.
  std::mt19937 rng(1);
  const keypose_bundle_t kb = msg::toLcm(randomBundle(rng, 1, 1));
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(kb.getEncodedSize()));
  kb.encode(buf.data(), 0, static_cast<int>(buf.size()));
  EXPECT_TRUE(decodeLcm<keypose_bundle_t>(buf.data(), buf.size()));
  for (std::size_t n = 0; n < buf.size(); n += 7) EXPECT_FALSE(decodeLcm<keypose_bundle_t>(buf.data(), n));
  buf.push_back(0);
  EXPECT_FALSE(decodeLcm<keypose_bundle_t>(buf.data(), buf.size()));
  // A bundle with a zero quaternion or an object without a model is refused, not crashed on.
  keypose_bundle_t bad = kb;
  for (double& q : bad.odom_pose.orientation) q = 0;
  EXPECT_FALSE(acceptBundle(bad, &why));
  bad = kb;
  bad.objects[0].num_cuboid = bad.objects[0].num_cylinder = bad.objects[0].num_ellipsoid = 0;
  bad.objects[0].cuboid.clear();
  bad.objects[0].cylinder.clear();
  bad.objects[0].ellipsoid.clear();
  EXPECT_FALSE(acceptBundle(bad, &why));
  EXPECT_FALSE(why.empty());
}
