#include "team/counters.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "app/clock.h"

namespace slide::team {

WallClock systemWallClock() { return app::wallMicros; }

CounterStore::CounterStore(std::string path, WallClock clock, std::int64_t max_ahead)
    : path_(std::move(path)), clock_(std::move(clock)), max_ahead_(max_ahead) {
  if (path_.empty()) return;
  std::ifstream in(path_);
  if (!in) return;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty()) continue;
    std::istringstream ss(line);
    std::string key;
    std::int32_t id = 0;
    std::int64_t c = 0;
    ss >> key;
    if (key == "own") ss >> c;
    else if (key == "sender") ss >> id >> c;
    else ss.setstate(std::ios::failbit);
    std::string rest;  // nothing may follow the numbers
    if (!ss || ss >> rest) {
      warnings_.push_back(path_ + ":" + std::to_string(lineno) + ": skipped malformed counter line '" + line + "'");
      continue;
    }
    if (key == "own") own_ = reserved_ = c;
    else accepted_[id] = Seen{c};
  }
  // Reserved beyond what any receiver accepts (a clock that ran ahead, a damaged file): going on
  // from there would silence this robot, so start again from the clock.
  const std::int64_t now = clock_();
  if (reserved_ > now && reserved_ - now > max_ahead_) own_ = reserved_ = now;
}

std::int64_t CounterStore::nextOwn() {
  own_ = std::max(own_ + 1, clock_());
  if (own_ > reserved_) {
    reserved_ = own_ + kBlock;
    // Before the counter is used, so a restart never reuses it. Should the write fail, the
    // clock still keeps a restart beyond it (unless the clock is set back meanwhile).
    write();
  }
  return own_;
}

CounterStore::Verdict CounterStore::check(std::int32_t sender, std::int64_t counter) {
  const std::int64_t now = clock_();
  const std::int64_t limit = now > INT64_MAX - max_ahead_ ? INT64_MAX : now + max_ahead_;
  if (counter > limit) return Verdict::Future;
  auto it = accepted_.find(sender);
  if (it != accepted_.end() && it->second.highest > limit) {  // persisted from a clock or sender gone wrong
    accepted_.erase(it);
    it = accepted_.end();
  }
  if (it == accepted_.end()) {
    accepted_[sender] = Seen{counter};
  } else {
    Seen& s = it->second;
    if (counter > s.highest) {
      const std::uint64_t shift = static_cast<std::uint64_t>(counter) - static_cast<std::uint64_t>(s.highest);
      // The old highest becomes bit shift-1; older ones move up (and out of the window).
      if (shift < static_cast<std::uint64_t>(kWindow)) s.below = (s.below << shift) | (std::uint64_t{1} << (shift - 1));
      else s.below = shift == static_cast<std::uint64_t>(kWindow) ? std::uint64_t{1} << 63 : 0;
      s.highest = counter;
    } else {
      const std::uint64_t back = static_cast<std::uint64_t>(s.highest) - static_cast<std::uint64_t>(counter);
      if (back == 0 || back > static_cast<std::uint64_t>(kWindow)) return Verdict::Replay;
      const std::uint64_t bit = std::uint64_t{1} << (back - 1);
      if (s.below & bit) return Verdict::Replay;
      s.below |= bit;
    }
  }
  dirty_ = true;
  return Verdict::New;
}

std::int64_t CounterStore::lastAccepted(std::int32_t sender) const {
  auto it = accepted_.find(sender);
  return it == accepted_.end() ? -1 : it->second.highest;
}

void CounterStore::save() {
  if (!dirty_) return;
  write();
}

void CounterStore::write() {
  if (path_.empty()) return;
  const std::string tmp = path_ + ".tmp";
  std::string error;
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "own " << reserved_ << "\n";
    for (const auto& [id, c] : accepted_) out << "sender " << id << " " << c.highest << "\n";
    out.flush();
    if (!out) error = "cannot write counter file " + tmp;
  }
  if (error.empty() && std::rename(tmp.c_str(), path_.c_str()) != 0) error = "cannot replace counter file " + path_;
  if (error.empty()) {
    dirty_ = false;
    return;
  }
  // The old file stays as it was; this state is written again at the next save.
  write_error_ = error + ": " + std::strerror(errno);
  std::remove(tmp.c_str());
  ++write_failures_;
  dirty_ = true;
}

}  // namespace slide::team
