// Map sharing as changes against the version peers hold: what goes out, what a receiver
// rebuilds, and what it refuses.
#include <gtest/gtest.h>

#include <random>

#include "team/map_sharing.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;

namespace {

SharedMap randomMap(std::mt19937& rng, int n, std::int32_t version) {
  SharedMap m;
  m.robot = 4;
  m.frame_robot = 4;
  m.version = version;
  m.utime = 1000 * version;
  for (int i = 0; i < n; ++i) m.objects.push_back(randomObject(rng, 10 + 3 * i));
  return m;
}

void shift(Object& o, const Eigen::Vector3d& d) {
  std::visit([&](auto& s) {
    using S = std::decay_t<decltype(s)>;
    if constexpr (std::is_same_v<S, Cuboid>) s.pose.translation() += d;
    else if constexpr (std::is_same_v<S, Cylinder>) s.root += d;
    else s.centroid += d;
  }, o.model);
}

const Object* byId(const SharedMap& m, std::int64_t id) {
  for (const Object& o : m.objects)
    if (o.id == id) return &o;
  return nullptr;
}

// The sender's map changes between versions; a receiver that got version 1 whole gets version 2
// as changes: moved, new and removed objects, nothing else, and rebuilds every object within the
// threshold (plus quantisation) of where the sender has it.
TEST(MapSharing, ChangesCarryWhatMovedAndTheReceiverRebuildsTheMap) {
  std::mt19937 rng(5);
  MapSharing sender, receiver;
  SharedMap v1 = randomMap(rng, 300, 1);
  sender.setOwn(v1);
  const auto first = sender.next({0});
  ASSERT_TRUE(first);
  EXPECT_EQ(first->kind, ChunkKind::Map);
  sender.sent(*first);
  ASSERT_TRUE(std::holds_alternative<SharedMap>(receiver.receive(first->kind, 4, first->version, first->payload)));
  EXPECT_EQ(receiver.held().at(4), 1);

  SharedMap v2 = v1;
  v2.version = 2;
  for (int i = 0; i < 10; ++i) shift(v2.objects[i], {0.5, -0.3, 0});     // moved: sent again
  for (int i = 10; i < 60; ++i) shift(v2.objects[i], {0.02, 0.03, 0});   // jitter: kept as it was
  v2.objects.erase(v2.objects.begin() + 100, v2.objects.begin() + 105);  // gone
  for (int i = 0; i < 7; ++i) v2.objects.push_back(randomObject(rng, 5000 + i));  // new
  sender.setOwn(v2);
  const auto second = sender.next({1, 1});
  ASSERT_TRUE(second);
  EXPECT_EQ(second->kind, ChunkKind::MapDelta);
  EXPECT_EQ(second->base, 1);
  EXPECT_LT(second->payload.size(), first->payload.size() / 5);
  sender.sent(*second);
  const auto got = receiver.receive(second->kind, 4, second->version, second->payload);
  ASSERT_TRUE(std::holds_alternative<SharedMap>(got));
  const SharedMap& map = std::get<SharedMap>(got);
  EXPECT_EQ(map.version, 2);
  EXPECT_EQ(map.utime, v2.utime);
  ASSERT_EQ(map.objects.size(), v2.objects.size());
  // Against what the whole map would have given (maps drop cylinder tilt and cuboid roll/pitch).
  const std::optional<SharedMap> whole = decodeMap(encodeMap(v2), 4, 2, nullptr);
  ASSERT_TRUE(whole);
  for (const Object& o : whole->objects) {
    const Object* r = byId(map, o.id);
    ASSERT_TRUE(r) << "object " << o.id;
    EXPECT_EQ(r->class_id, o.class_id);
    EXPECT_LE((r->position() - o.position()).norm(), 0.1 + 0.04) << "object " << o.id;
  }
  EXPECT_FALSE(byId(map, v1.objects[100].id));
  // Version 3 against version 2 as both sides rebuilt it: only what moved since.
  SharedMap v3 = v2;
  v3.version = 3;
  shift(v3.objects[0], {1, 0, 0});
  sender.setOwn(v3);
  const auto third = sender.next({2});
  ASSERT_TRUE(third);
  EXPECT_EQ(third->kind, ChunkKind::MapDelta);
  const auto d = decodeMapDelta(third->payload, nullptr);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->changed.size(), 1u);
  EXPECT_TRUE(d->removed.empty());
  sender.sent(*third);
  ASSERT_TRUE(std::holds_alternative<SharedMap>(receiver.receive(third->kind, 4, 3, third->payload)));
}

TEST(MapSharing, WholeMapForPeersWithoutAKnownVersion) {
  std::mt19937 rng(6);
  MapSharing sender;
  sender.setOwn(randomMap(rng, 50, 1));
  sender.sent(*sender.next({}));
  SharedMap v2 = randomMap(rng, 50, 2);
  sender.setOwn(v2);
  EXPECT_EQ(sender.next({0})->kind, ChunkKind::Map);     // a peer holding nothing
  EXPECT_EQ(sender.next({1, 0})->kind, ChunkKind::Map);  // one of them
  EXPECT_EQ(sender.next({7})->kind, ChunkKind::Map);     // a version this sender does not know
  SharedMap dup = v2;
  dup.objects[1].id = dup.objects[0].id;  // ids that do not name one object each
  sender.setOwn(dup);
  EXPECT_EQ(sender.next({1})->kind, ChunkKind::Map);
}

TEST(MapSharing, ChangesAgainstAVersionNotHeldOrOldMapsAreRefused) {
  std::mt19937 rng(7);
  MapSharing sender, receiver, late;
  sender.setOwn(randomMap(rng, 40, 1));
  const auto v1 = *sender.next({});
  sender.sent(v1);
  SharedMap m2 = *sender.own();
  m2.version = 2;
  shift(m2.objects[3], {2, 0, 0});
  sender.setOwn(m2);
  const auto v2 = *sender.next({1});
  ASSERT_EQ(v2.kind, ChunkKind::MapDelta);
  // A robot that missed version 1 cannot use the changes; its heartbeat asks for more.
  EXPECT_EQ(std::get<Drop>(late.receive(v2.kind, 4, 2, v2.payload)), Drop::MapBaseMissing);
  EXPECT_TRUE(late.held().empty());
  ASSERT_TRUE(std::holds_alternative<SharedMap>(receiver.receive(v1.kind, 4, 1, v1.payload)));
  ASSERT_TRUE(std::holds_alternative<SharedMap>(receiver.receive(v2.kind, 4, 2, v2.payload)));
  EXPECT_EQ(std::get<Drop>(receiver.receive(v1.kind, 4, 1, v1.payload)), Drop::Stale);
  // Changes that remove an object the base does not hold, or cut short, are malformed.
  MapDelta bad;
  bad.base = 2;
  bad.removed = {999999};
  EXPECT_EQ(std::get<Drop>(receiver.receive(ChunkKind::MapDelta, 4, 3, encodeMapDelta(bad))), Drop::Malformed);
  Bytes cut = v2.payload;
  cut.resize(cut.size() / 2);
  EXPECT_EQ(std::get<Drop>(receiver.receive(ChunkKind::MapDelta, 4, 4, cut)), Drop::Malformed);
  EXPECT_EQ(receiver.held().at(4), 2);
}

}  // namespace
