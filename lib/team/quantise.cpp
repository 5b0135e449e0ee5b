#include "team/quantise.h"

#include <cmath>

#include "geometry/pose.h"

namespace slide::team {

std::optional<std::int64_t> quantise(double v, double unit, std::int64_t limit) {
  if (!std::isfinite(v)) return std::nullopt;
  const double q = std::round(v / unit);
  if (std::abs(q) > static_cast<double>(limit)) return std::nullopt;
  return static_cast<std::int64_t>(q);
}

std::optional<std::uint8_t> quantiseU8(double v, double unit) {
  const auto q = quantise(v, unit, 255);
  if (!q || *q < 0) return std::nullopt;
  return static_cast<std::uint8_t>(*q);
}

std::uint16_t quantiseTurn16(double angle) {
  if (!std::isfinite(angle)) return 0;
  const double turns = wrapAngle(angle) / (2 * M_PI);  // (-0.5, 0.5]
  return static_cast<std::uint16_t>(std::llround(turns * 65536.0) & 0xffff);
}

double turn16ToAngle(std::uint16_t q) {
  return wrapAngle(static_cast<double>(static_cast<std::int16_t>(q)) * (2 * M_PI / 65536.0));
}

std::uint8_t quantiseTurn8(double angle) {
  if (!std::isfinite(angle)) return 0;
  return static_cast<std::uint8_t>(std::llround(wrapAngle(angle) / (2 * M_PI) * 256.0) & 0xff);
}

double turn8ToAngle(std::uint8_t q) {
  return wrapAngle(static_cast<double>(static_cast<std::int8_t>(q)) * (2 * M_PI / 256.0));
}

std::optional<std::uint8_t> quantiseSigma(double s) {
  if (s == 0) return 0;
  if (!(s > 0) || !std::isfinite(s)) return std::nullopt;
  const double q = std::round(std::log2(s) * 16 + 200);
  if (q < 1 || q > 255) return std::nullopt;
  return static_cast<std::uint8_t>(q);
}

double sigmaOf(std::uint8_t q) { return q == 0 ? 0.0 : std::exp2((q - 200) / 16.0); }

}  // namespace slide::team
