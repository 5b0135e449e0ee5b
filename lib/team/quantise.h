#pragma once
// Fixed-step quantisation for the compact team encodings: a value v travels as the integer
// q = round(v / unit) and comes back as q * unit (error at most unit / 2). A value that is not
// finite or whose q exceeds the stated limit does not quantise: callers then escape it (write
// it as float32 under a flag) instead of clamping it.
#include <cstdint>
#include <optional>

namespace slide::team {

std::optional<std::int64_t> quantise(double v, double unit, std::int64_t limit);
// Non-negative values in one byte: q in 0..255.
std::optional<std::uint8_t> quantiseU8(double v, double unit);
// An angle (any finite value) as a fraction of a full turn in 16 bits; back in (-pi, pi].
std::uint16_t quantiseTurn16(double angle);
double turn16ToAngle(std::uint16_t q);
// The same in 8 bits (1/256 turn: within 0.71 degrees).
std::uint8_t quantiseTurn8(double angle);
double turn8ToAngle(std::uint8_t q);
// A standard deviation in one byte on a log scale: 0 is zero, q in 1..255 is 2^((q - 200) / 16)
// (1.7e-4 .. 10.9, steps of 4.4%: relative error at most 2.2%). nullopt when negative, not
// finite, or outside that range.
std::optional<std::uint8_t> quantiseSigma(double s);
double sigmaOf(std::uint8_t q);

}  // namespace slide::team
