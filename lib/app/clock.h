#pragma once
// The daemons' clocks, one function each: steady time in seconds (periods and timeouts) and in
// microseconds (the peer-sync engine's time), both from an arbitrary origin; wall time in
// microseconds since the Unix epoch (the utime stamped on messages, counters that must survive a
// restart) and in seconds (the viewer's replay clock, which runs against recorded utimes).
#include <cstdint>

namespace slide::app {

double steadySeconds();
std::int64_t steadyMicros();
std::int64_t wallMicros();
double wallSeconds();

}  // namespace slide::app
