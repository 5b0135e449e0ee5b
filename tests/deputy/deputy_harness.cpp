#include "deputy_harness.h"

#include <signal.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>

#include "msg/procman_convert.h"

namespace slide::test {
namespace {

int64_t nowUs() {
  timeval tv;
  gettimeofday(&tv, nullptr);
  return int64_t(tv.tv_sec) * 1000000 + tv.tv_usec;
}

}  // namespace

pid_t startDeputy(const std::string& id) {
  const std::string exe = std::string(SLIDE_BINARY_DIR) + "/bin/slide-deputy";
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    execl(exe.c_str(), exe.c_str(), "--id", id.c_str(), "--lcm-url", kTestUrl, "--discovery-ms", "300",
          "--shutdown-wait", "2", "--log-level", "warn", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

int waitExit(pid_t pid, double timeout_s) {
  const int64_t end = nowUs() + static_cast<int64_t>(timeout_s * 1e6);
  int status = 0;
  while (nowUs() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid) return status;
    usleep(20000);
  }
  return -1;
}

SheriffStub::SheriffStub() : lcm_(kTestUrl) {
  if (!lcm_.good()) throw std::runtime_error("no LCM");
  lcm_.subscribe("PM_INFO", &SheriffStub::onInfo, this);
  lcm_.subscribe("PM_OUTPUT", &SheriffStub::onOutput, this);
}

void SheriffStub::onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m) {
  info = *m;
  have_info = true;
}

void SheriffStub::onOutput(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::output_t* m) {
  for (int i = 0; i < m->num_commands; ++i) output += m->command_ids[i] + ": " + m->text[i];
}

void SheriffStub::order(const std::string& deputy, const std::vector<procman::DesiredCommand>& cmds, int64_t utime_offset_us) {
  deputy_ = deputy;
  orders_ = cmds;
  offset_us_ = utime_offset_us;
  next_send_us_ = 0;
  spin(0);
}

void SheriffStub::spin(double seconds) {
  const int64_t end = nowUs() + static_cast<int64_t>(seconds * 1e6);
  do {
    const int64_t now = nowUs();
    if (!deputy_.empty() && now >= next_send_us_) {
      const procman_lcm::orders_t m = msg::makeOrders(deputy_, "test-sheriff", now + offset_us_, orders_);
      lcm_.publish("PM_ORDERS", &m);
      next_send_us_ = now + 500000;
    }
    lcm_.handleTimeout(20);
  } while (nowUs() < end);
}

bool SheriffStub::waitFor(const std::function<bool(const procman_lcm::deputy_info_t&)>& pred, double timeout_s) {
  const int64_t end = nowUs() + static_cast<int64_t>(timeout_s * 1e6);
  while (nowUs() < end) {
    spin(0.02);
    if (have_info && pred(info)) return true;
  }
  return false;
}

const procman_lcm::cmd_status_t* findCommand(const procman_lcm::deputy_info_t& info, const std::string& id) {
  for (const auto& c : info.cmds)
    if (c.cmd.command_id == id) return &c;
  return nullptr;
}

procman::DesiredCommand command(const std::string& id, const std::string& exec, int32_t runid, bool force_quit,
                                bool respawn) {
  procman::DesiredCommand d;
  d.spec.id = id;
  d.spec.exec = exec;
  d.spec.group = "test";
  d.spec.auto_respawn = respawn;
  d.spec.stop_signal = SIGTERM;
  d.spec.stop_time_allowed = 1;
  d.desired_runid = runid;
  d.force_quit = force_quit;
  return d;
}

}  // namespace slide::test
