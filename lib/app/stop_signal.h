#pragma once
// The flags a daemon's loop watches, set from signal handlers: SIGINT and SIGTERM ask it to stop
// (it finishes the current step, sends its last status and exits 0); SIGUSR1 asks it to write its
// files now (the optimizer's outputs). The handlers only set a flag.
#include <atomic>

namespace slide::app {

// Installs the SIGINT and SIGTERM handlers.
void installStopHandlers();
bool stopRequested();
// The stop flag itself, for a long computation that polls it (the optimizer aborts a solve).
const std::atomic<bool>* stopFlag();

// Installs the SIGUSR1 handler.
void installWriteHandler();
// True once per SIGUSR1 (the flag is cleared).
bool takeWriteRequest();

}  // namespace slide::app
