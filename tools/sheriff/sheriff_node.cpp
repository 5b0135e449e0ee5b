#include "sheriff_node.h"

#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <spdlog/spdlog.h>
#include <stdexcept>

#include "msg/procman_convert.h"
#include "procman_lcm/discovery_t.hpp"
#include "procman/output_lines.h"
#include "procman/status_table.h"

namespace slide {
namespace {

int64_t nowUs() {
  timeval tv;
  gettimeofday(&tv, nullptr);
  return int64_t(tv.tv_sec) * 1000000 + tv.tv_usec;
}

}  // namespace

SheriffNode::SheriffNode(const procman::PmdConfig& cfg, const SheriffOptions& opts)
    : cfg_(cfg), opts_(opts), lcm_(opts.lcm_url), model_(cfg.commands) {
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at " + opts.lcm_url);
  lcm_.subscribe("PM_INFO", &SheriffNode::onInfo, this);
  if (opts_.show_output) lcm_.subscribe("PM_OUTPUT", &SheriffNode::onOutput, this);
}

void SheriffNode::onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m) {
  const auto deputies = model_.deputies();
  if (std::find(deputies.begin(), deputies.end(), m->deputy_id) == deputies.end()) return;
  if (!model_.heardFrom(m->deputy_id)) spdlog::info("deputy '{}' reports {} commands", m->deputy_id, m->ncmds);
  model_.onDeputyInfo(m->deputy_id, msg::commandReports(*m));
}

void SheriffNode::onOutput(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::output_t* m) {
  for (int i = 0; i < m->num_commands; ++i) {
    for (const std::string& line : procman::outputLines(m->text[i]))
      std::printf("[%s/%s] %s\n", m->deputy_id.c_str(), m->command_ids[i].c_str(), line.c_str());
  }
  std::fflush(stdout);
}

void SheriffNode::spin(double seconds) {
  const int64_t end = nowUs() + static_cast<int64_t>(seconds * 1e6);
  while (nowUs() < end) lcm_.handleTimeout(std::max<int>(1, std::min<int64_t>(20, (end - nowUs()) / 1000)));
}

void SheriffNode::sendOrders(int64_t now) {
  for (const std::string& d : model_.deputies()) {
    const procman_lcm::orders_t m = msg::makeOrders(d, opts_.id, now, model_.ordersFor(d));
    lcm_.publish("PM_ORDERS", &m);
  }
}

int SheriffNode::run() {
  // Deputies answer PM_DISCOVER with PM_INFO at once, so the table fills without waiting.
  procman_lcm::discovery_t hello;
  hello.utime = nowUs();
  hello.transmitter_id = opts_.id;
  hello.nonce = getpid();
  lcm_.publish("PM_DISCOVER", &hello);
  if (opts_.script.empty()) {
    spin(opts_.listen_s);
    std::fputs(procman::formatStatusTable(model_).c_str(), stdout);
    return 0;
  }
  procman::ScriptRunner runner(cfg_, model_, opts_.script, opts_.wait_timeout_s);
  const int64_t hear_end = nowUs() + static_cast<int64_t>(opts_.deputy_timeout_s * 1e6);
  auto allHeard = [&]() {
    for (const std::string& d : model_.deputies())
      if (!model_.heardFrom(d)) return false;
    return true;
  };
  while (!allHeard() && nowUs() < hear_end) spin(0.05);
  for (const std::string& d : model_.deputies())
    if (!model_.heardFrom(d)) spdlog::warn("no PM_INFO from deputy '{}' yet; its commands will wait for it", d);

  spdlog::info("running script '{}'", opts_.script);
  procman::ScriptRunner::Result result = procman::ScriptRunner::Result::kRunning;
  int64_t next_orders = 0;
  while (result == procman::ScriptRunner::Result::kRunning) {
    bool changed = false;
    const int64_t now = nowUs();
    result = runner.step(now, &changed);
    for (const std::string& line : runner.takeMessages()) spdlog::info("{}", line);
    if (changed || now >= next_orders) {
      sendOrders(now);
      next_orders = now + 1000000;
    }
    spin(0.02);
  }
  const int64_t linger_end = nowUs() + static_cast<int64_t>(opts_.linger_s * 1e6);
  while (nowUs() < linger_end) {
    sendOrders(nowUs());
    spin(std::min(1.0, (linger_end - nowUs()) / 1e6));
  }
  sendOrders(nowUs());
  std::fputs(procman::formatStatusTable(model_).c_str(), stdout);
  std::fflush(stdout);
  if (result == procman::ScriptRunner::Result::kFailed) {
    for (const std::string& f : runner.failures()) spdlog::error("{}", f);
    return 1;
  }
  spdlog::info("script '{}' done", opts_.script);
  return 0;
}

}  // namespace slide
