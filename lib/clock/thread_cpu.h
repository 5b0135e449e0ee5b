#pragma once
// The calling thread's CPU time (threadCpuMs), the figure place-recognition budgets and every
// benchmark's CPU columns count.

namespace slide::clock {

// CPU time the calling thread has used, in milliseconds. Budgets and benchmarks count this
// rather than wall time: it does not grow while the thread waits for a core on a loaded machine.
double threadCpuMs();

}  // namespace slide::clock
