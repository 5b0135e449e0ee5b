#include "backend/odometry_envelope.h"

#include <algorithm>
#include <cmath>

namespace slide::backend {

void OdometryDrift::add(const OdometryStep& s) {
  translation_var += s.translation_sigma * s.translation_sigma;
  heading_shift += std::sqrt(yaw_var) * s.length_m;  // heading error so far moves this step sideways
  yaw_var += s.yaw_sigma * s.yaw_sigma;
}

void OdometryTotals::add(const OdometryStep& s) {
  translation_var += s.translation_sigma * s.translation_sigma;
  yaw_var += s.yaw_sigma * s.yaw_sigma;
  length_m += s.length_m;
}

OdometryTotals OdometryTotals::operator-(const OdometryTotals& o) const {
  return {translation_var - o.translation_var, yaw_var - o.yaw_var, length_m - o.length_m};
}

OdometryTotals OdometryTotals::operator+(const OdometryTotals& o) const {
  return {translation_var + o.translation_var, yaw_var + o.yaw_var, length_m + o.length_m};
}

double driftRadius(const OdometryTotals& s) {
  return std::sqrt(std::max(0.0, s.translation_var + s.yaw_var * s.length_m * s.length_m / 3.0));
}

EnvelopeCheck checkAgainstOdometry(const OdometryDrift& drift, const Pose& odom_a_b, const Pose& T_a_b,
                                   const OdometryEnvelope& envelope) {
  EnvelopeCheck c;
  c.allowed_m = std::max(envelope.floor_m, envelope.gate_sigmas * (std::sqrt(drift.translation_var) + drift.heading_shift));
  c.allowed_deg = std::max(envelope.floor_deg, envelope.gate_sigmas * std::sqrt(drift.yaw_var) * 180.0 / M_PI);
  const Pose d = odom_a_b.inverse() * T_a_b;
  c.translation_m = d.translation().norm();
  c.yaw_deg = std::abs(wrapAngle(xyzYawOf(d)[3])) * 180.0 / M_PI;
  c.inside = c.translation_m <= c.allowed_m && c.yaw_deg <= c.allowed_deg;
  return c;
}

EnvelopeCheck checkAgainstOdometry(const std::vector<OdometryStep>& steps, const Pose& odom_a_b, const Pose& T_a_b,
                                   const OdometryEnvelope& envelope) {
  OdometryDrift drift;
  for (const OdometryStep& s : steps) drift.add(s);
  return checkAgainstOdometry(drift, odom_a_b, T_a_b, envelope);
}

}  // namespace slide::backend
