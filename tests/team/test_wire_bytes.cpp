// slide::team::lcmWireBytes against what LCM really sends: datagrams caught on the multicast group of a
// ttl=0 URL with a plain UDP socket, for a small message, one larger than an Ethernet frame and
// one that LCM must fragment.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "team/messages.h"

namespace {

constexpr const char* kGroup = "239.255.76.124";
constexpr int kPort = 7724;
constexpr std::size_t kIpUdp = 28;  // one IPv4 and one UDP header

// The UDP payload sizes of every datagram that reaches the group within `ms` of the last.
std::vector<std::size_t> datagrams(int fd, int ms) {
  std::vector<std::size_t> out;
  std::vector<char> buf(1 << 17);
  pollfd p{fd, POLLIN, 0};
  while (poll(&p, 1, ms) > 0) {
    const ssize_t n = recv(fd, buf.data(), buf.size(), 0);
    if (n <= 0) break;
    out.push_back(static_cast<std::size_t>(n));
  }
  return out;
}

int joinGroup() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  setsockopt(fd, SOL_SOCKET, SO_REUSEPORT, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(kPort);
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) return -1;
  ip_mreq mreq{};
  inet_pton(AF_INET, kGroup, &mreq.imr_multiaddr);
  mreq.imr_interface.s_addr = htonl(INADDR_ANY);
  if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) != 0) return -1;
  return fd;
}

TEST(LcmWireBytes, MatchesTheDatagramsLcmSends) {
  const int fd = joinGroup();
  ASSERT_GE(fd, 0) << "cannot join " << kGroup << ":" << kPort;
  lcm::LCM bus(std::string("udpm://") + kGroup + ":" + std::to_string(kPort) + "?ttl=0");
  ASSERT_TRUE(bus.good());
  const std::string channel = "TEAM_CHUNK";
  for (const std::size_t payload : {std::size_t{300}, std::size_t{3000}, std::size_t{100000}}) {
    const std::vector<char> data(payload, 'x');
    ASSERT_EQ(bus.publish(channel, data.data(), static_cast<unsigned>(payload)), 0);
    const std::vector<std::size_t> got = datagrams(fd, 300);
    ASSERT_FALSE(got.empty()) << "no datagram for a " << payload << "-byte message";
    // Each datagram costs its UDP payload, a UDP header and one IP header per 1480-byte fragment.
    std::size_t wire = 0;
    for (std::size_t n : got) wire += n + 8 + 20 * ((n + 8 + 1479) / 1480);
    EXPECT_EQ(slide::team::lcmWireBytes(channel, payload), wire) << payload << "-byte message in " << got.size() << " datagrams";
    EXPECT_EQ(got.size(), payload < 65000 ? 1u : 2u);
  }
  close(fd);
}

TEST(LcmWireBytes, CountsIpFragmentsOfALargeDatagram) {
  // 8 + 11 + 1453 = 1472 bytes of UDP payload fill one 1500-byte packet exactly; one more byte
  // needs a second IP packet.
  EXPECT_EQ(slide::team::lcmWireBytes("TEAM_CHUNK", 1453), 1472 + kIpUdp);
  EXPECT_EQ(slide::team::lcmWireBytes("TEAM_CHUNK", 1454), 1473 + kIpUdp + 20);
  EXPECT_EQ(slide::team::lcmWireBytes("TEAM_CHUNK", 1454, 9000), 1473 + kIpUdp);
}

}  // namespace
