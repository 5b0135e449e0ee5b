// LCM's generated encoders write a double through an int64_t pointer; compiled with GCC's strict
// aliasing (-O2) a value stored just before encode() goes out as the old one (0 here). Every
// target that includes the types is built with -fno-strict-aliasing (cmake/SlideLcmTypes.cmake);
// this fails if that flag goes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "slide/odometry_t.hpp"

TEST(LcmEncoding, DoublesSetJustBeforeEncodeGoOutAsSet) {
  slide::odometry_t m{};
  m.pose.position[0] = 12.5;
  m.pose.position[1] = NAN;
  m.pose.orientation[0] = -0.25;
  std::vector<unsigned char> buf(static_cast<std::size_t>(m.getEncodedSize()));
  ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  slide::odometry_t d{};
  ASSERT_EQ(d.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  EXPECT_EQ(d.pose.position[0], 12.5);
  EXPECT_TRUE(std::isnan(d.pose.position[1]));
  EXPECT_EQ(d.pose.orientation[0], -0.25);
}
