#pragma once
// One background thread for the optimizer's full solves: it runs one task at a time (a solve
// of a graph snapshot, which owns everything it touches), and the owner collects the result
// when done() says so. cancel() asks the running task to stop (tasks poll the flag between
// solver iterations) without waiting for it; the destructor cancels and joins.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace slide::backend {

class SolveWorker {
 public:
  // A task runs on the worker thread; it should return soon after `cancel` becomes true.
  using Task = std::function<void(const std::atomic<bool>& cancel)>;

  SolveWorker();
  ~SolveWorker();
  SolveWorker(const SolveWorker&) = delete;
  SolveWorker& operator=(const SolveWorker&) = delete;

  // Starts `task`; false (and nothing started) while the previous one is still running.
  bool start(Task task);
  bool busy() const { return busy_.load(); }
  // Sets the running task's cancel flag; returns at once.
  void cancel() { cancel_.store(true); }
  // Blocks until no task runs.
  void wait();

 private:
  void loop();

  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  Task next_;
  bool quit_ = false;
  std::atomic<bool> busy_{false};
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace slide::backend
