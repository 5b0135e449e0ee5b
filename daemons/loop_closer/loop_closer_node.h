#pragma once
// The loop-closer daemon's logic without the LCM loop: the own map, the own trajectory and
// peers' maps in (decoded messages), place recognition through LoopCloser, loop closures out
// through an injected publisher, and the counts its status reports. Bad input (non-finite or
// absurd objects, maps over the size cap, a failing check) is dropped, counted and logged.
#include <string>

#include "app/channels.h"
#include "config/config.h"
#include "msg/publisher.h"
#include "place/loop_closer.h"
#include "slide/object_map_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide {

struct LoopCloserChannels {
  std::string own_map = app::channels::kOwnMap;
  std::string peer_maps = app::channels::kPeerMap;
  std::string trajectory = app::channels::kTrajectory;
  std::string loop_closures = app::channels::kLoopClosure;
  std::string status = app::channels::kDaemonStatus;
};

// Reads the config's `lcm:` section (url and channel names) into `channels`; returns its url,
// empty when it names none.
std::string readLoopCloserBus(const ConfigNode& cfg, LoopCloserChannels& channels);

class LoopCloserNode {
 public:
  LoopCloserNode(place::LoopCloserParams params, LoopCloserChannels channels, msg::Publisher publish);

  // A map on `channel`, own (robot == params.robot) or a peer's; maps not in their own robot's
  // frame are skipped. `now_s`: steady seconds.
  void onMap(const std::string& channel, const object_map_t& m, double now_s);
  // The own trajectory (others' are ignored), for intra-robot checks.
  void onTrajectory(const trajectory_t& m);
  // Runs the checks due at `now_s` and publishes the closures the consensus filter confirms.
  void poll(double now_s);

  const place::LoopCloser& closer() const { return closer_; }
  long published() const { return published_; }
  long droppedObjects() const { return dropped_objects_; }
  // Inputs refused: objects dropped, maps over the size cap, checks over budget.
  long droppedInputs() const;

 private:
  void publish(const place::LoopClosure& lc);

  place::LoopCloserParams params_;
  LoopCloserChannels channels_;
  msg::Publisher publish_;
  place::LoopCloser closer_;
  long dropped_objects_ = 0;
  long published_ = 0;
  long budget_exceeded_ = 0;
  std::string last_reason_;
};

}  // namespace slide
