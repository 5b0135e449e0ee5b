#include "log_player.h"

#include <algorithm>
#include <filesystem>
#include <regex>
#include <stdexcept>

namespace slide {

namespace fs = std::filesystem;

namespace {
bool sourceFromName(const std::string& path, LogSource& s) {
  static const std::regex name(R"((robot|team)(\d+)[^/]*\.lcmlog)");
  std::smatch m;
  const std::string file = fs::path(path).filename().string();
  if (!std::regex_match(file, m, name)) return false;
  s = {path, m[1] == "team", std::stoi(m[2])};
  return true;
}
}  // namespace

std::vector<LogSource> logSourcesOf(const std::string& path) {
  static const std::regex named(R"((team:)?(\d+)=(.+))");
  std::smatch m;
  if (std::regex_match(path, m, named)) return {{m[3].str(), m[1].matched, std::stoi(m[2])}};
  std::vector<LogSource> out;
  if (fs::is_directory(path)) {
    const fs::path logs = fs::is_directory(fs::path(path) / "logs") ? fs::path(path) / "logs" : fs::path(path);
    for (const auto& e : fs::directory_iterator(logs)) {
      LogSource s;
      if (e.is_regular_file() && sourceFromName(e.path().string(), s)) out.push_back(s);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
    if (out.empty()) throw std::runtime_error(logs.string() + ": no robot<N>.lcmlog or team<N>.lcmlog in it");
    return out;
  }
  LogSource s;
  if (!fs::exists(path)) throw std::runtime_error(path + ": no such run folder or LCM log");
  if (!sourceFromName(path, s))
    throw std::runtime_error(path + ": cannot tell whose log it is; name it robot<N>.lcmlog / team<N>.lcmlog or "
                                    "pass N=" + path + " (robot N's bus) or team:N=" + path);
  return {s};
}

LogPlayer::LogPlayer(std::vector<LogSource> sources, ViewerNode& node, viewer::Scene& scene, bool follow, double wall)
    : sources_(std::move(sources)), node_(node), scene_(scene), follow_(follow), clock_(0, 0, follow, wall) {
  for (const LogSource& s : sources_) readers_.push_back(std::make_unique<io::LcmLogReader>(s.path));
  readMore(wall);
}

void LogPlayer::addSources(const std::vector<LogSource>& sources) {
  for (const LogSource& s : sources) {
    if (std::any_of(sources_.begin(), sources_.end(), [&s](const LogSource& o) { return o.path == s.path; })) continue;
    readers_.push_back(std::make_unique<io::LcmLogReader>(s.path));
    sources_.push_back(s);
  }
}

std::size_t LogPlayer::readMore(double wall) {
  std::vector<Event> fresh;
  for (std::size_t i = 0; i < readers_.size(); ++i) {
    const bool team = sources_[i].team;
    auto wanted = [this, team](const std::string& c) {
      return team ? node_.wantsTeamChannel(c) : node_.wantsRobotChannel(c);
    };
    io::LcmLogEvent ev;
    while (readers_[i]->next(ev, wanted))
      fresh.push_back({static_cast<double>(ev.utime) * 1e-6, static_cast<int>(i), ev.channel, std::move(ev.data)});
  }
  std::stable_sort(fresh.begin(), fresh.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  for (Event& e : fresh) {
    if (e.t <= applied_) {  // from a log that lagged behind the others: into the scene now
      feed(e);
      events_.insert(events_.begin() + static_cast<long>(next_), std::move(e));
      ++next_;
    } else {
      events_.push_back(std::move(e));
    }
  }
  std::stable_sort(events_.begin() + static_cast<long>(next_), events_.end(),
                   [](const Event& a, const Event& b) { return a.t < b.t; });
  if (!events_.empty() && !timed_) {
    clock_ = viewer::ReplayClock(events_.front().t, events_.back().t, follow_, wall);
    timed_ = true;
  }
  if (!events_.empty()) clock_.extend(events_.back().t);
  return fresh.size();
}

void LogPlayer::feed(const Event& e) {
  const LogSource& s = sources_[static_cast<std::size_t>(e.source)];
  if (s.team) node_.onTeamBus(s.robot, e.channel, e.data.data(), e.data.size(), e.t);
  else node_.onRobotBus(s.robot, e.channel, e.data.data(), e.data.size(), e.t);
}

void LogPlayer::advance(double wall) {
  const double pos = clock_.position(wall);
  if (pos < applied_) {
    scene_.reset();
    node_.reset();
    next_ = 0;
  }
  while (next_ < events_.size() && events_[next_].t <= pos) feed(events_[next_++]);
  applied_ = pos;
  scene_.tick(pos);
}

std::uint64_t LogPlayer::corruptLogBytes() const {
  std::uint64_t n = 0;
  for (const auto& r : readers_) n += r->counts().corrupt_bytes;
  return n;
}

}  // namespace slide
