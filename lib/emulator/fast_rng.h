#pragma once
// SplitMix64 with Box-Muller normals: a fast random generator whose sequence depends only on
// its seed (no implementation-defined std distributions), for per-point sensor noise and the
// detection emulator.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace slide::emulator {

struct FastRng {
  explicit FastRng(uint64_t seed) : state(seed) {}
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  bool chance(double p) { return uniform() < p; }
  int below(int n) { return n > 0 ? static_cast<int>(uniform() * n) : 0; }  // [0, n)
  double normal() {
    if (has_spare) {
      has_spare = false;
      return spare;
    }
    const double u1 = std::max(uniform(), 1e-300), u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare = r * std::sin(2 * M_PI * u2);
    has_spare = true;
    return r * std::cos(2 * M_PI * u2);
  }
  // Poisson-distributed count with mean `mean` (Knuth; means here are small).
  int poisson(double mean) {
    if (!(mean > 0)) return 0;
    const double limit = std::exp(-std::min(mean, 50.0));
    int k = 0;
    for (double p = uniform(); p > limit && k < 1000; p *= uniform()) ++k;
    return k;
  }
  uint64_t state;
  double spare = 0;
  bool has_spare = false;
};

}  // namespace slide::emulator
