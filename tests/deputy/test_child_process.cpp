// Spawning children: output pipe, exit status 127 for a missing program, group signals.
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "procman/child_process.h"

using namespace slide::procman;

namespace {

// Reads the child's output until EOF (or 5 s) and reaps it; returns (wait status, output).
std::pair<int, std::string> finish(const SpawnedChild& c) {
  std::string out;
  char buf[256];
  for (int i = 0; i < 500; ++i) {
    pollfd p{c.output_fd, POLLIN, 0};
    poll(&p, 1, 10);
    const ssize_t n = read(c.output_fd, buf, sizeof(buf));
    if (n > 0) out.append(buf, buf + n);
    if (n == 0) break;
  }
  close(c.output_fd);
  int st = -1;
  waitpid(c.pid, &st, 0);
  return {st, out};
}

// Alive and not a zombie (an orphan may wait a while for init to reap it).
bool running(int pid) {
  FILE* f = std::fopen(("/proc/" + std::to_string(pid) + "/stat").c_str(), "r");
  if (!f) return false;
  char state = 'X';
  const int n = std::fscanf(f, "%*d (%*[^)]) %c", &state);
  std::fclose(f);
  return n == 1 && state != 'Z' && state != 'X';
}

}  // namespace

TEST(ChildProcess, CapturesStdoutAndStderrAndEnv) {
  const auto [st, out] = finish(spawnChild("GREETING=hello sh -c 'echo $GREETING; echo oops >&2; exit 3'"));
  EXPECT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 3);
  EXPECT_EQ(out, "hello\noops\n");
}

TEST(ChildProcess, MissingProgramExits127WithAMessage) {
  const auto [st, out] = finish(spawnChild("/nonexistent/prog --x"));
  EXPECT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 127);
  EXPECT_NE(out.find("cannot execute /nonexistent/prog"), std::string::npos) << out;
  EXPECT_THROW(spawnChild("prog 'unterminated"), std::invalid_argument);
}

TEST(ChildProcess, SignalReachesTheWholeGroup) {
  const SpawnedChild c = spawnChild("sh -c 'sleep 30 & echo $!; wait'");
  std::string line;
  char ch;
  for (int i = 0; i < 500 && line.find('\n') == std::string::npos; ++i) {
    pollfd p{c.output_fd, POLLIN, 0};
    poll(&p, 1, 10);
    if (read(c.output_fd, &ch, 1) == 1) line += ch;
  }
  const int grandchild = std::stoi(line);
  ASSERT_TRUE(running(grandchild));
  EXPECT_TRUE(signalChild(c.pid, SIGTERM));
  const auto [st, out] = finish(c);
  EXPECT_TRUE(WIFSIGNALED(st));
  for (int i = 0; i < 100 && running(grandchild); ++i) usleep(10000);
  EXPECT_FALSE(running(grandchild)) << "the grandchild survived";
  EXPECT_FALSE(signalChild(0, SIGTERM));
}
