#include "peak_memory.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>

namespace slide::bench_place {

namespace {
// A "Key:   123 kB" line of /proc/self/status in kB; negative when absent.
double statusKb(const std::string& key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.compare(0, key.size() + 1, key + ":") == 0) {
      std::istringstream in(line.substr(key.size() + 1));
      double kb = -1;
      in >> kb;
      return kb;
    }
  return -1;
}
}  // namespace

PeakMemory::PeakMemory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // reset the peak resident set (Linux >= 4.0)
  clear.flush();
  rss0_kb_ = statusKb("VmRSS");
  ok_ = clear.good() && rss0_kb_ >= 0;
}

double PeakMemory::extraMb() const {
  if (!ok_) return std::numeric_limits<double>::quiet_NaN();
  const double hwm = statusKb("VmHWM");
  return hwm < 0 ? std::numeric_limits<double>::quiet_NaN() : std::max(0.0, hwm - rss0_kb_) / 1024.0;
}

}  // namespace slide::bench_place
