#include "viewer/replay_clock.h"

#include <algorithm>
#include <cmath>

namespace slide::viewer {

ReplayClock::ReplayClock(double start, double end, bool live, double wall)
    : start_(start), end_(std::max(start, end)), live_(live), anchor_pos_(start), anchor_wall_(wall) {}

double ReplayClock::clamp(double pos) const { return std::min(std::max(pos, start_), end_); }

void ReplayClock::extend(double end) { end_ = std::max(end_, end); }

double ReplayClock::position(double wall) const {
  if (live_) return end_;
  if (paused_) return clamp(anchor_pos_);
  return clamp(anchor_pos_ + (wall - anchor_wall_) * speed_);
}

void ReplayClock::anchor(double wall) {
  anchor_pos_ = position(wall);
  anchor_wall_ = wall;
}

void ReplayClock::play(double wall) {
  anchor(wall);
  paused_ = false;
}

void ReplayClock::pause(double wall) {
  anchor(wall);
  live_ = false;
  paused_ = true;
}

void ReplayClock::setSpeed(double speed, double wall) {
  if (!std::isfinite(speed)) return;
  anchor(wall);
  speed_ = std::min(std::max(speed, kMinSpeed), kMaxSpeed);
}

void ReplayClock::seek(double pos, double wall) {
  if (!std::isfinite(pos)) return;
  live_ = false;
  anchor_pos_ = clamp(pos);
  anchor_wall_ = wall;
}

void ReplayClock::goLive() {
  live_ = true;
  paused_ = false;
}

nlohmann::json ReplayClock::status(double wall) const {
  return {{"start", start_}, {"end", end_}, {"position", position(wall)},
          {"paused", paused_}, {"live", live_}, {"speed", speed_}};
}

}  // namespace slide::viewer
