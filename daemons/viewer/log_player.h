#pragma once
// Recorded runs into the viewer: the LCM event logs of a run folder (logs/robot<N>.lcmlog, one
// robot's bus each, and logs/team<N>.lcmlog, the team bus as robot N's host heard it: what
// `./slide demo` records) or single logs, played into a ViewerNode in log time under a
// viewer::ReplayClock (pause, speed, seek, live). Only the channels the viewer draws are kept
// in memory. With `follow`, logs still being written are read again as they grow (a demo
// watched while it runs). Jumping back replays from the start into a reset scene.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/lcm_log.h"
#include "viewer/replay_clock.h"
#include "viewer_node.h"

namespace slide {

struct LogSource {
  std::string path;
  bool team = false;  // a team-bus log (else a robot bus)
  int robot = 0;      // the robot whose bus it is, or who heard the team bus
};

// The logs of `path`: a run folder (its logs/robot<N>.lcmlog and logs/team<N>.lcmlog), a file
// named robot<N>*.lcmlog or team<N>*.lcmlog, or "N=file" / "team:N=file". Throws naming the
// path when it holds no log or a name says no robot.
std::vector<LogSource> logSourcesOf(const std::string& path);

class LogPlayer {
 public:
  // Reads what the logs hold now; throws when a log cannot be opened.
  LogPlayer(std::vector<LogSource> sources, ViewerNode& node, viewer::Scene& scene, bool follow, double wall);

  // Reads what was appended since (follow mode); returns the number of new events.
  std::size_t readMore(double wall);
  // Adds the logs of `sources` not played yet (a run folder whose loggers started late).
  void addSources(const std::vector<LogSource>& sources);
  // Feeds the node every event up to the clock's position at `wall` (resetting first when the
  // clock went back) and ticks the scene there.
  void advance(double wall);
  viewer::ReplayClock& clock() { return clock_; }
  const viewer::ReplayClock& clock() const { return clock_; }
  std::size_t events() const { return events_.size(); }
  std::uint64_t corruptLogBytes() const;

 private:
  struct Event {
    double t;
    int source;
    std::string channel;
    std::vector<std::uint8_t> data;
  };
  void feed(const Event& e);

  std::vector<LogSource> sources_;
  std::vector<std::unique_ptr<io::LcmLogReader>> readers_;
  ViewerNode& node_;
  viewer::Scene& scene_;
  bool follow_;
  std::vector<Event> events_;  // by time
  std::size_t next_ = 0;       // events_[0, next_) are in the scene
  double applied_ = -1e300;    // log time the scene is at
  bool timed_ = false;         // the clock spans the events (there were any)
  viewer::ReplayClock clock_;
};

}  // namespace slide
