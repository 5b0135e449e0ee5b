#include "deputy_node.h"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <random>
#include <spdlog/spdlog.h>
#include <stdexcept>

#include "msg/procman_convert.h"
#include "procman/child_process.h"

namespace slide {
namespace {

int64_t nowUs() {
  timeval tv;
  gettimeofday(&tv, nullptr);
  return int64_t(tv.tv_sec) * 1000000 + tv.tv_usec;
}

std::string describeStatus(int st) {
  if (WIFSIGNALED(st)) return std::string("killed by signal ") + std::to_string(WTERMSIG(st)) + " (" + strsignal(WTERMSIG(st)) + ")";
  return "exited with status " + std::to_string(WEXITSTATUS(st));
}

}  // namespace

DeputyNode::DeputyNode(const DeputyOptions& opts) : opts_(opts), lcm_(opts.lcm_url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at " + opts.lcm_url);
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&set, s);
  sigprocmask(SIG_BLOCK, &set, nullptr);
  signal_fd_ = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
  if (signal_fd_ < 0) throw std::runtime_error(std::string("signalfd: ") + std::strerror(errno));
  std::random_device rd;
  nonce_ = (int64_t(rd()) << 32) ^ getpid();
}

DeputyNode::~DeputyNode() {
  for (const auto& [fd, id] : output_fds_) close(fd);
  if (signal_fd_ >= 0) close(signal_fd_);
}

void DeputyNode::say(const std::string& command_id, const std::string& text, int64_t now) {
  output_.add(command_id, text, now);
}

void DeputyNode::execute(const std::vector<procman::Action>& actions, int64_t now) {
  for (const procman::Action& a : actions) {
    auto it = table_.commands().find(a.id);
    if (it == table_.commands().end()) continue;
    if (a.kind == procman::Action::kSignal) {
      spdlog::info("[{}] signal {} to pid {}", a.id, a.signal, it->second.pid);
      if (!procman::signalChild(it->second.pid, a.signal)) say(a.id, "failed to send signal " + std::to_string(a.signal) + "\n", now);
      continue;
    }
    try {
      const procman::SpawnedChild child = procman::spawnChild(it->second.spec.exec);
      table_.markStarted(a.id, child.pid, now);
      output_fds_[child.output_fd] = a.id;
      pid_fd_[child.pid] = child.output_fd;
      spdlog::info("[{}] started pid {}: {}", a.id, child.pid, it->second.spec.exec);
    } catch (const std::exception& e) {
      spdlog::error("[{}] cannot start: {}", a.id, e.what());
      say(a.id, std::string("cannot start: ") + e.what() + "\n", now);
      table_.markStartFailed(a.id, now);
    }
    info_dirty_ = true;
  }
}

void DeputyNode::readOutput(int fd, int64_t now) {
  char buf[4096];
  while (true) {
    const ssize_t n = read(fd, buf, sizeof(buf));
    if (n > 0) {
      say(output_fds_[fd], std::string(buf, buf + n), now);
      continue;
    }
    if (n == 0 || (errno != EAGAIN && errno != EINTR)) closeOutput(fd, now);
    return;
  }
}

void DeputyNode::closeOutput(int fd, int64_t) {
  close(fd);
  output_fds_.erase(fd);
  for (auto it = pid_fd_.begin(); it != pid_fd_.end(); ++it)
    if (it->second == fd) {
      pid_fd_.erase(it);
      break;
    }
}

void DeputyNode::reapChildren(int64_t now) {
  int status = 0;
  pid_t pid;
  while ((pid = waitpid(-1, &status, WNOHANG)) > 0) {
    auto fd = pid_fd_.find(pid);
    if (fd != pid_fd_.end()) {
      const int f = fd->second;
      if (output_fds_.count(f)) readOutput(f, now);
      if (output_fds_.count(f)) closeOutput(f, now);
    }
    usage_.erase(pid);
    const procman::ExitOutcome out = table_.markExited(pid, status, now);
    if (!out.known) continue;
    spdlog::info("[{}] pid {} {}", out.id, pid, describeStatus(status));
    if (WIFSIGNALED(status)) say(out.id, describeStatus(status) + "\n", now);
    if (out.removed) spdlog::info("[{}] removed", out.id);
    execute(out.actions, now);
    info_dirty_ = true;
  }
}

void DeputyNode::handleSignals(int64_t now) {
  signalfd_siginfo si;
  while (read(signal_fd_, &si, sizeof(si)) == sizeof(si)) {
    if (si.ssi_signo == SIGCHLD) {
      reapChildren(now);
    } else if (!exiting_) {
      spdlog::info("signal {} ({}): stopping all commands", si.ssi_signo, strsignal(si.ssi_signo));
      exiting_ = true;
      exit_deadline_us_ = now + static_cast<int64_t>((opts_.shutdown_wait_s + 1.0) * 1e6);
      execute(table_.stopAll(now, opts_.shutdown_wait_s), now);
    }
  }
  reapChildren(now);  // SIGCHLD may coalesce with others
}

void DeputyNode::sampleUsage() {
  const auto sys = procman::readSystemTimes();
  mem_ = procman::readMemoryInfo();
  if (!sys) return;
  cpu_load_ = procman::cpuShare(last_sys_.busy_jiffies, sys->busy_jiffies, last_sys_, *sys);
  for (const auto& [id, c] : table_.commands()) {
    if (c.pid == 0) continue;
    const auto pt = procman::readProcessTimes(c.pid);
    if (!pt) continue;
    auto it = usage_.find(c.pid);
    const uint64_t used = pt->user_jiffies + pt->system_jiffies;
    if (it != usage_.end()) {
      const uint64_t before = it->second.last.user_jiffies + it->second.last.system_jiffies;
      it->second.cpu = procman::cpuShare(before, used, last_sys_, *sys);
      it->second.last = *pt;
    } else {
      usage_[c.pid] = Usage{*pt, 0.f};
    }
  }
  last_sys_ = *sys;
}

void DeputyNode::publishInfo(int64_t now) {
  std::vector<procman::CommandReport> reports = table_.reports();
  for (procman::CommandReport& r : reports) {
    auto it = usage_.find(r.pid);
    if (r.pid == 0 || it == usage_.end()) continue;
    r.cpu_usage = it->second.cpu;
    r.mem_vsize_bytes = it->second.last.vsize_bytes;
    r.mem_rss_bytes = it->second.last.rss_bytes;
  }
  const procman_lcm::deputy_info_t m = msg::makeDeputyInfo(opts_.id, now, cpu_load_, mem_, reports);
  lcm_.publish("PM_INFO", &m);
  info_dirty_ = false;
}

void DeputyNode::publishOutput(int64_t now) {
  if (output_.empty()) return;
  const procman_lcm::output_t m = msg::makeOutput(opts_.id, now, output_.take());
  lcm_.publish("PM_OUTPUT", &m);
}

void DeputyNode::onOrders(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::orders_t* m) {
  const int64_t now = nowUs();
  if (exiting_ || m->deputy_id != opts_.id) return;
  if (procman::ordersAreStale(m->utime, now)) {
    spdlog::warn("ignoring stale orders from {} ({} s old): check the clocks", m->sheriff_id, (now - m->utime) / 1000000);
    say("", "ignoring stale orders from " + m->sheriff_id + "\n", now);
    return;
  }
  bool changed = false;
  execute(table_.applyOrders(msg::desiredCommands(*m), now, &changed), now);
  if (changed) info_dirty_ = true;
}

void DeputyNode::onDiscover(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::discovery_t* m) {
  const int64_t now = nowUs();
  if (discovering(now)) {
    if (m->transmitter_id == opts_.id && m->nonce != nonce_) {
      spdlog::error("another deputy with id '{}' is running: exiting", opts_.id);
      exit_code_ = 2;
    }
  } else {
    info_dirty_ = true;  // answer discovery with our state
  }
}

void DeputyNode::onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m) {
  if (discovering(nowUs()) && m->deputy_id == opts_.id) {
    spdlog::error("another deputy with id '{}' reports on PM_INFO: exiting", opts_.id);
    exit_code_ = 2;
  }
}

int DeputyNode::run() {
  start_us_ = nowUs();
  inbox_.subscribe("PM_DISCOVER", &DeputyNode::onDiscover, this);
  inbox_.subscribe("PM_INFO", &DeputyNode::onInfo, this);
  spdlog::info("deputy '{}' on {}: discovery for {} ms", opts_.id, opts_.lcm_url, opts_.discovery_ms);
  int64_t next_discover = 0, next_info = 0;
  bool active = false;
  sampleUsage();
  while (exit_code_ < 0) {
    int64_t now = nowUs();
    if (!active && discovering(now) && now >= next_discover) {
      procman_lcm::discovery_t d;
      d.utime = now;
      d.transmitter_id = opts_.id;
      d.nonce = nonce_;
      lcm_.publish("PM_DISCOVER", &d);
      next_discover = now + 200000;
    } else if (!active && !discovering(now)) {
      active = true;
      inbox_.unsubscribe("PM_INFO");
      inbox_.subscribe("PM_ORDERS", &DeputyNode::onOrders, this);
      spdlog::info("deputy '{}' active", opts_.id);
      info_dirty_ = true;
    }
    std::vector<pollfd> fds{{lcm_.getFileno(), POLLIN, 0}, {signal_fd_, POLLIN, 0}};
    for (const auto& [fd, id] : output_fds_) fds.push_back({fd, POLLIN, 0});
    poll(fds.data(), fds.size(), output_.empty() ? 50 : 10);
    now = nowUs();
    if (fds[0].revents & POLLIN) lcm_.handleTimeout(0);
    if (fds[1].revents & POLLIN) handleSignals(now);
    for (std::size_t i = 2; i < fds.size(); ++i)
      if (fds[i].revents & (POLLIN | POLLHUP | POLLERR) && output_fds_.count(fds[i].fd)) readOutput(fds[i].fd, now);
    execute(table_.tick(now), now);
    if (output_.due(now)) publishOutput(now);
    if (active && now >= next_info) {
      sampleUsage();
      info_dirty_ = true;
      next_info = now + 1000000;
    }
    if (active && info_dirty_) publishInfo(now);
    if (exiting_ && (!table_.anyRunning() || now > exit_deadline_us_)) exit_code_ = 0;
  }
  const int64_t now = nowUs();
  publishOutput(now);
  if (active) publishInfo(now);
  spdlog::info("deputy '{}' exiting", opts_.id);
  return exit_code_;
}

}  // namespace slide
