#include "team/counters.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace slide::team {

CounterStore::CounterStore(std::string path) : path_(std::move(path)) {
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
    ss >> key;
    if (key == "own") {
      ss >> reserved_;
      own_ = reserved_;
    } else if (key == "sender") {
      std::int32_t id;
      std::int64_t c;
      ss >> id >> c;
      accepted_[id] = Seen{c};
    } else {
      ss.setstate(std::ios::failbit);
    }
    if (!ss) throw std::runtime_error(path_ + ":" + std::to_string(lineno) + ": malformed counter line '" + line + "'");
  }
}

std::int64_t CounterStore::nextOwn() {
  ++own_;
  if (own_ > reserved_) {
    reserved_ = own_ + kBlock;
    write();  // before the counter is used, so a restart never reuses it
  }
  return own_;
}

bool CounterStore::accept(std::int32_t sender, std::int64_t counter) {
  auto it = accepted_.find(sender);
  if (it == accepted_.end()) {
    accepted_[sender] = Seen{counter};
  } else {
    Seen& s = it->second;
    if (counter > s.highest) {
      const std::int64_t shift = counter - s.highest;
      // The old highest becomes bit shift-1; older ones move up (and out of the window).
      if (shift < kWindow) s.below = (s.below << shift) | (std::uint64_t{1} << (shift - 1));
      else s.below = shift == kWindow ? std::uint64_t{1} << 63 : 0;
      s.highest = counter;
    } else {
      const std::int64_t back = s.highest - counter;  // >= 0
      if (back == 0 || back > kWindow) return false;
      const std::uint64_t bit = std::uint64_t{1} << (back - 1);
      if (s.below & bit) return false;
      s.below |= bit;
    }
  }
  dirty_ = true;
  return true;
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
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "own " << reserved_ << "\n";
    for (const auto& [id, c] : accepted_) out << "sender " << id << " " << c.highest << "\n";
    out.flush();
    if (!out) throw std::runtime_error("cannot write counter file " + tmp);
  }
  if (std::rename(tmp.c_str(), path_.c_str()) != 0) throw std::runtime_error("cannot replace counter file " + path_);
  dirty_ = false;
}

}  // namespace slide::team
