#pragma once
// How far a robot's own odometry can plausibly be wrong between two of its key poses: the
// random walk of the per-step odometry sigmas (yaw accumulates as the root sum of squares,
// and a heading error displaces every later step by its length), times a gate, with floors.
// A loop closure or a merged estimate that moves the robot further than this from what its
// odometry says contradicts the odometry and is refused or undone.
#include <vector>

#include "geometry/pose.h"

namespace slide::backend {

struct OdometryEnvelope {
  double gate_sigmas = 3.0;    // allowed deviation in sigmas of the accumulated drift
  double floor_m = 1.0;        // never tighter than this translation...
  double floor_deg = 3.0;      // ...and this yaw
};

struct OdometryStep {
  double length_m = 0;          // translation of the step
  double translation_sigma = 0; // per-step sigmas (the odometry factor's)
  double yaw_sigma = 0;
};

struct EnvelopeCheck {
  bool inside = true;
  double translation_m = 0, yaw_deg = 0;            // deviation found
  double allowed_m = 0, allowed_deg = 0;            // what the envelope allows
};

// The drift accumulated over odometry steps taken in order (add one at a time, so a walk along
// a trajectory checks every key pose against its start in linear time).
struct OdometryDrift {
  double translation_var = 0, yaw_var = 0, heading_shift = 0;
  void add(const OdometryStep& s);
};

// Sums over a robot's odometry steps from its first key pose: a stretch's are the difference
// of its two ends' (and a stretch joined to another through a loop closure, their sum).
struct OdometryTotals {
  double translation_var = 0, yaw_var = 0, length_m = 0;
  void add(const OdometryStep& s);
  OdometryTotals operator-(const OdometryTotals& o) const;
  OdometryTotals operator+(const OdometryTotals& o) const;
};

// One sigma of how far the odometry may have put one end of a stretch from the other: the
// translation random walk, and the sideways shift of a heading error that grows as a random
// walk along it (length times the end's yaw sigma over sqrt 3), added in quadrature.
double driftRadius(const OdometryTotals& stretch);

// drift: of the odometry steps from key pose a to key pose b; odom_a_b: the relative pose
// odometry gives; T_a_b: the relative pose to check (a loop closure or an estimate).
EnvelopeCheck checkAgainstOdometry(const OdometryDrift& drift, const Pose& odom_a_b, const Pose& T_a_b,
                                   const OdometryEnvelope& envelope);
// The same with the steps from a to b, in order.
EnvelopeCheck checkAgainstOdometry(const std::vector<OdometryStep>& steps, const Pose& odom_a_b, const Pose& T_a_b,
                                   const OdometryEnvelope& envelope);

}  // namespace slide::backend
