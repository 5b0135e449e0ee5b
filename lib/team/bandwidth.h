#pragma once
// Team-bus traffic per peer: bytes sent to it (broadcasts shared out among the peers in
// reach) and received from it, and the rates that matter for the budget: bytes per second,
// per landmark and per metre travelled.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "team/rate_limiter.h"

namespace slide::team {

struct PeerTraffic {
  std::int32_t peer = 0;
  double bytes_sent = 0;      // attributed to this peer
  double bytes_received = 0;  // everything heard from it
  std::uint64_t messages_sent = 0, messages_received = 0;
};

struct TrafficFigures {
  std::int32_t peer = 0;
  double sent_bytes_per_s = 0, received_bytes_per_s = 0;
  double received_per_landmark = 0;  // bytes heard from the peer per landmark in its shared map
  double received_per_metre = 0;     // bytes heard from the peer per metre of its trajectory held
};

class BandwidthMeter {
 public:
  explicit BandwidthMeter(Micros start) : start_(start) {}
  // A message of `bytes` sent to `peers` (one for unicast, all in reach for a broadcast).
  void sent(const std::vector<std::int32_t>& peers, std::size_t bytes);
  void received(std::int32_t peer, std::size_t bytes);
  double totalSent() const { return total_sent_; }
  double totalReceived() const { return total_received_; }
  const std::map<std::int32_t, PeerTraffic>& peers() const { return peers_; }
  // Figures for one peer given its landmark count and metres travelled (0: reported as 0).
  TrafficFigures figures(std::int32_t peer, Micros now, std::size_t landmarks, double metres) const;
  std::string summary(std::int32_t peer, Micros now, std::size_t landmarks, double metres) const;

 private:
  Micros start_;
  double total_sent_ = 0, total_received_ = 0;
  std::uint64_t broadcasts_unattributed_ = 0;
  std::map<std::int32_t, PeerTraffic> peers_;
};

}  // namespace slide::team
