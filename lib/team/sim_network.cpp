#include "team/sim_network.h"

#include <filesystem>

namespace slide::team {

SimNetwork::SimNetwork(std::vector<SyncConfig> configs, std::string state_root, SimLinkModel link, std::uint64_t seed)
    : configs_(std::move(configs)), state_root_(std::move(state_root)), link_(std::move(link)), rng_(seed) {
  nodes_.resize(configs_.size());
  clock_offset_.assign(configs_.size(), 0);
  delivered_.resize(configs_.size());
  delivered_bundles_.resize(configs_.size());
  for (std::size_t i = 0; i < configs_.size(); ++i) makeNode(i);
}

void SimNetwork::makeNode(std::size_t i) {
  std::string dir;
  if (!state_root_.empty()) {
    dir = state_root_ + "/robot" + std::to_string(configs_[i].robot);
    std::filesystem::create_directories(dir);
  }
  nodes_[i].reset();
  // The simulated time is every node's wall clock too (from 2026-01-01): runs are deterministic.
  nodes_[i] = std::make_unique<PeerSyncNode>(configs_[i], dir, now_, channels_,
                                             [this, i] { return kSimEpoch + now_ + clock_offset_[i]; });
}

void SimNetwork::restart(std::size_t i) { makeNode(i); }

std::size_t SimNetwork::wireBytes(const TeamMessage& m) const {
  if (auto* h = std::get_if<Heartbeat>(&m)) return lcmWireBytes(channels_.heartbeat, encodedSize(*h));
  if (auto* c = std::get_if<Chunk>(&m)) return lcmWireBytes(channels_.chunk, encodedSize(*c));
  return lcmWireBytes(channels_.ack, encodedSize(std::get<Ack>(m)));
}

void SimNetwork::transmit(std::size_t from, const TeamMessage& m) {
  if (on_send) on_send(from, m);
  bytes_sent_ += static_cast<double>(wireBytes(m));
  ++messages_sent_;
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t to = 0; to < nodes_.size(); ++to) {
    if (to == from) continue;
    if (link_.link_up && !link_.link_up(configs_[from].robot, configs_[to].robot, now_)) continue;
    if (u(rng_) < link_.loss) continue;
    const int copies = u(rng_) < link_.duplicate ? 2 : 1;
    for (int k = 0; k < copies; ++k) {
      const double delay = link_.latency_s + link_.jitter_s * u(rng_);
      medium_.push({now_ + static_cast<Micros>(delay * 1e6), order_++, to, m});
    }
  }
}

void SimNetwork::inject(std::size_t from_index, const TeamMessage& m) { transmit(from_index, m); }

void SimNetwork::run(Micros dt, Micros tick) {
  const Micros end = now_ + dt;
  while (now_ < end) {
    now_ = std::min(end, now_ + tick);
    while (!medium_.empty() && medium_.top().at <= now_) {
      InFlight f = medium_.top();
      medium_.pop();
      std::visit([&](const auto& msg) { nodes_[f.to]->receive(msg, now_); }, f.msg);
    }
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      TickOutput out = nodes_[i]->tick(now_);
      for (const auto& h : out.heartbeats) transmit(i, h);
      for (const auto& a : out.acks) transmit(i, a);
      for (const auto& c : out.chunks) transmit(i, c);
      while (auto b = nodes_[i]->nextDelivery()) {
        delivered_[i].emplace_back(b->robot, b->seq);
        nodes_[i]->confirmDelivered(b->robot, b->seq);
        delivered_bundles_[i].push_back(std::move(*b));
      }
    }
  }
}

}  // namespace slide::team
