#pragma once
// Where a replay stands in its log: log time as a function of wall time under pause, speed,
// seek and "live" (always at the newest event, for a log still being written). Times are
// seconds; log times are clamped to [start, end]. Pure arithmetic, no threads.
#include <nlohmann/json.hpp>

namespace slide::viewer {

class ReplayClock {
 public:
  static constexpr double kMinSpeed = 0.05, kMaxSpeed = 64.0;

  // A log spanning [start, end]; plays from start at speed 1 (live: from the end, following it).
  ReplayClock(double start, double end, bool live, double wall);

  // The log grew (following a live log): its newest event is at `end`.
  void extend(double end);
  double position(double wall) const;
  void play(double wall);
  void pause(double wall);
  // Clamped to [kMinSpeed, kMaxSpeed]; a non-finite speed is ignored.
  void setSpeed(double speed, double wall);
  // To log time `pos` (clamped; a non-finite one is ignored); leaves live mode.
  void seek(double pos, double wall);
  void goLive();

  bool paused() const { return paused_; }
  bool live() const { return live_; }
  double speed() const { return speed_; }
  double start() const { return start_; }
  double end() const { return end_; }
  // {"start", "end", "position", "paused", "live", "speed"} for the page.
  nlohmann::json status(double wall) const;

 private:
  void anchor(double wall);  // folds the elapsed play into anchor_pos_
  double clamp(double pos) const;

  double start_, end_;
  bool live_, paused_ = false;
  double speed_ = 1.0;
  double anchor_pos_, anchor_wall_;
};

}  // namespace slide::viewer
