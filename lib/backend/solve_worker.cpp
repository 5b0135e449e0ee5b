#include "backend/solve_worker.h"

namespace slide::backend {

SolveWorker::SolveWorker() : thread_([this] { loop(); }) {}

SolveWorker::~SolveWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
    cancel_.store(true);
  }
  wake_.notify_all();
  thread_.join();
}

bool SolveWorker::start(Task task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (busy_.load() || quit_) return false;
    cancel_.store(false);
    next_ = std::move(task);
    busy_.store(true);
  }
  wake_.notify_all();
  return true;
}

void SolveWorker::wait() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !busy_.load(); });
}

void SolveWorker::loop() {
  for (;;) {
    Task task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return quit_ || next_; });
      if (!next_) return;  // quit with nothing queued
      task = std::move(next_);
      next_ = nullptr;
    }
    // A task's exception must not take the process down: the result it fills says it failed.
    try {
      task(cancel_);
    } catch (...) {
    }
    bool quit;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      busy_.store(false);
      quit = quit_;
    }
    idle_.notify_all();
    if (quit) return;
  }
}

}  // namespace slide::backend
