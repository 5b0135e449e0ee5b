#include "procman/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "procman/exec_args.h"

namespace slide::procman {
namespace {

[[noreturn]] void childExec(const ExecArgs& args, int out_fd) {
  setpgid(0, 0);
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGCHLD, SIGPIPE}) signal(s, SIG_DFL);
  const int devnull = open("/dev/null", O_RDONLY);
  if (devnull >= 0) dup2(devnull, STDIN_FILENO);
  dup2(out_fd, STDOUT_FILENO);
  dup2(out_fd, STDERR_FILENO);
  for (const auto& [name, value] : args.env) setenv(name.c_str(), value.c_str(), 1);
  std::vector<char*> argv;
  for (const std::string& a : args.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execvp(argv[0], argv.data());
  const std::string msg = "cannot execute " + args.argv[0] + ": " + std::strerror(errno) + "\n";
  if (write(STDERR_FILENO, msg.data(), msg.size()) < 0) {}
  _exit(127);
}

}  // namespace

SpawnedChild spawnChild(const std::string& exec) {
  const ExecArgs args = splitExec(exec);  // parse before forking: errors stay in the parent
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) childExec(args, fds[1]);  // dup2 clears O_CLOEXEC on 1 and 2
  setpgid(pid, pid);  // also done in the child; whichever runs first wins
  close(fds[1]);
  fcntl(fds[0], F_SETFL, fcntl(fds[0], F_GETFL) | O_NONBLOCK);
  return {pid, fds[0]};
}

bool signalChild(pid_t pid, int sig) {
  if (pid <= 0) return false;
  if (kill(-pid, sig) == 0) return true;
  return kill(pid, sig) == 0;
}

}  // namespace slide::procman
