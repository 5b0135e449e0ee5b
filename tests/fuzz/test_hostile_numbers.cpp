// Numbers a daemon receives that no robot could report (issue 16 finding 4): peer sync
// refuses bundles with NaN / infinite / absurd odom_sigma, poses and objects beyond its
// frame bounds (they overflowed the team codec's floats), and the Delaunay triangulation of
// SlideGraph returns instead of letting OpenCV throw on an object 3e9 m away.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../../daemons/peer_sync/team_msg.h"
#include "hostile_messages.h"
#include "place/delaunay.h"

using namespace slide;

TEST(HostileNumbers, PeerSyncRefusesBundlesWithAbsurdSigmasOrPositions) {
  std::string why;
  ASSERT_TRUE(team::acceptBundle(fuzz::bundle(0, 1), &why)) << why;
  const float inf = std::numeric_limits<float>::infinity();
  for (float s : {std::nanf(""), inf, -inf, -1.f, 1e30f}) {
    keypose_bundle_t m = fuzz::bundle(0, 1);
    m.odom_sigma[2] = s;
    why.clear();
    EXPECT_FALSE(team::acceptBundle(m, &why)) << "odom_sigma " << s;
    EXPECT_NE(why.find("odom_sigma"), std::string::npos) << why;
  }
  for (double x : {1e39, -1e300, 3e9}) {
    keypose_bundle_t m = fuzz::bundle(0, 1);
    m.odom_pose.position[0] = x;
    EXPECT_FALSE(team::acceptBundle(m, &why)) << "odom_pose x " << x;
    m = fuzz::bundle(0, 1);
    m.objects[0].cylinder[0].root[1] = static_cast<float>(x > 3.4e38 || x < -3.4e38 ? inf : x);
    EXPECT_FALSE(team::acceptBundle(m, &why)) << "object y " << x;
    object_map_t map = fuzz::objectMap(0);
    map.objects[1].cylinder[0].root[0] = static_cast<float>(x > 3.4e38 || x < -3.4e38 ? inf : x);
    EXPECT_FALSE(team::fromLcm(map, &why)) << "map object x " << x;
  }
  ASSERT_TRUE(team::fromLcm(fuzz::objectMap(0), &why)) << why;
}

TEST(HostileNumbers, DelaunayOfAMapWithAnObjectBillionsOfMetresAwayDoesNotThrow) {
  std::vector<Eigen::Vector2d> pts{{0, 0}, {10, 0}, {0, 10}, {10, 10}, {5, 3}};
  ASSERT_FALSE(place::delaunay2d(pts).empty());
  pts.push_back({3e9, 0});
  EXPECT_NO_THROW(place::delaunay2d(pts));
  pts.back() = {0, -1e300};
  EXPECT_NO_THROW(place::delaunay2d(pts));
}
