#include "team/bandwidth.h"

#include <cstdio>

namespace slide::team {

void BandwidthMeter::sent(const std::vector<std::int32_t>& peers, std::size_t bytes) {
  total_sent_ += static_cast<double>(bytes);
  if (peers.empty()) {
    ++broadcasts_unattributed_;
    return;
  }
  const double share = static_cast<double>(bytes) / static_cast<double>(peers.size());
  for (std::int32_t p : peers) {
    auto& t = peers_[p];
    t.peer = p;
    t.bytes_sent += share;
    ++t.messages_sent;
  }
}

void BandwidthMeter::received(std::int32_t peer, std::size_t bytes) {
  total_received_ += static_cast<double>(bytes);
  auto& t = peers_[peer];
  t.peer = peer;
  t.bytes_received += static_cast<double>(bytes);
  ++t.messages_received;
}

TrafficFigures BandwidthMeter::figures(std::int32_t peer, Micros now, std::size_t landmarks, double metres) const {
  TrafficFigures f;
  f.peer = peer;
  auto it = peers_.find(peer);
  if (it == peers_.end()) return f;
  const double secs = std::max(1e-6, 1e-6 * static_cast<double>(now - start_));
  f.sent_bytes_per_s = it->second.bytes_sent / secs;
  f.received_bytes_per_s = it->second.bytes_received / secs;
  if (landmarks > 0) f.received_per_landmark = it->second.bytes_received / static_cast<double>(landmarks);
  if (metres > 0) f.received_per_metre = it->second.bytes_received / metres;
  return f;
}

std::string BandwidthMeter::summary(std::int32_t peer, Micros now, std::size_t landmarks, double metres) const {
  const TrafficFigures f = figures(peer, now, landmarks, metres);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "peer %d: sent %.0f B/s, received %.0f B/s, %.0f B/landmark (%zu), %.0f B/m (%.1f m)", peer,
                f.sent_bytes_per_s, f.received_bytes_per_s, f.received_per_landmark, landmarks,
                f.received_per_metre, metres);
  return buf;
}

}  // namespace slide::team
