// A daemon that is busy (a full solve, a burst of peer bundles) must not lose what arrived
// meanwhile: LCM keeps 30 messages per subscription by default and drops the rest silently.
#include <gtest/gtest.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "msg/inbox.h"

namespace {

const char* kUrl = "udpm://239.255.76.126:7726?ttl=0&recv_buf_size=4194304";

// Publishes `count` messages of `size` bytes on `channel` while nobody handles, then handles
// until quiet; returns how many reached the handler.
int deliveredAfterBusySpell(lcm::LCM& sub, slide::msg::Inbox& inbox, const std::string& channel, int count, int size) {
  int got = 0;
  inbox.subscribeBytes(channel, [&](const std::string&, const void*, std::size_t) { ++got; });
  lcm::LCM pub(kUrl);
  const std::vector<char> data(static_cast<std::size_t>(size), 'x');
  for (int i = 0; i < count; ++i) {
    pub.publish(channel, data.data(), static_cast<unsigned>(data.size()));
    if (i % 100 == 99) usleep(2000);  // the kernel's socket buffer is not what is tested
  }
  usleep(300000);
  while (sub.handleTimeout(300) > 0) {
  }
  return got;
}

TEST(InboxQueue, ABusyDaemonGetsEveryMessageThatArrivedMeanwhile) {
  lcm::LCM sub(kUrl);
  ASSERT_TRUE(sub.good());
  slide::msg::Inbox inbox(sub);
  EXPECT_EQ(deliveredAfterBusySpell(sub, inbox, "PEER_BUNDLE", 500, 1500), 500);
}

TEST(InboxQueue, ASensorStreamWithASmallCapacitySkipsFrames) {
  lcm::LCM sub(kUrl);
  ASSERT_TRUE(sub.good());
  slide::msg::Inbox inbox(sub);
  int got = 0;
  inbox.subscribeBytes("SCAN", [&](const std::string&, const void*, std::size_t) { ++got; });
  inbox.setQueueCapacity("SCAN", 5);
  lcm::LCM pub(kUrl);
  const std::vector<char> data(20000, 'x');
  for (int i = 0; i < 40; ++i) pub.publish("SCAN", data.data(), static_cast<unsigned>(data.size()));
  usleep(300000);
  while (sub.handleTimeout(300) > 0) {
  }
  EXPECT_GE(got, 1);
  EXPECT_LE(got, 6);
}

}  // namespace
