#pragma once
// Peak memory of one stretch of work in this process (Linux): the resident-set high-water mark
// (VmHWM) is reset through /proc/self/clear_refs before the work and read after it; the figure is
// that peak less the resident set before. It counts what the work touched, the thread's stack and
// anything other threads did meanwhile (the place bench runs one thread).
#include <string>

namespace slide::bench_place {

class PeakMemory {
 public:
  // Resets the high-water mark and notes the resident set; ok() is false when /proc does not allow it.
  PeakMemory();
  bool ok() const { return ok_; }
  // Megabytes above the resident set at construction, peak since then (NaN when !ok()).
  double extraMb() const;

 private:
  bool ok_ = false;
  double rss0_kb_ = 0;
};

}  // namespace slide::bench_place
