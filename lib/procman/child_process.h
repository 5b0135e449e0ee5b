#pragma once
// Starting and signalling child processes. Each child runs in its own process group with
// stdin from /dev/null and stdout+stderr into one non-blocking pipe read by the caller.
#include <sys/types.h>

#include <string>

namespace slide::procman {

struct SpawnedChild {
  pid_t pid = -1;
  int output_fd = -1;  // read end of the child's stdout/stderr pipe (non-blocking)
};

// Forks and execs the exec string (see exec_args.h; the program is searched in PATH).
// Throws std::runtime_error when the exec string is invalid or fork/pipe fail; a program
// that cannot be executed makes the child exit with status 127 and a message on its output.
SpawnedChild spawnChild(const std::string& exec);

// Sends sig to the child's process group (falls back to the pid). Returns false on failure.
bool signalChild(pid_t pid, int sig);

}  // namespace slide::procman
