#pragma once

namespace slide {

// CPU time the calling thread has used, in milliseconds. Budgets and benchmarks count this
// rather than wall time: it does not grow while the thread waits for a core on a loaded machine.
double threadCpuMs();

}  // namespace slide
