#pragma once
// Random bundles and team configurations shared by the team tests.
#include <random>

#include "objects/keypose_bundle.h"
#include "team/codec.h"
#include "team/message_auth.h"
#include "team/sync_config.h"
#include "team/team_keys.h"

namespace slide::team::testing {

inline Object randomObject(std::mt19937& rng, std::int64_t id) {
  std::uniform_real_distribution<double> u(-15, 15), s(0.1, 3);
  Object o;
  o.id = id;
  const int shape = static_cast<int>(rng() % 3);
  if (shape == 0) {
    Cuboid b;
    b.pose = poseFromXyzYaw(u(rng), u(rng), 0.8, u(rng));
    if (rng() % 2) b.pose = poseFromXyzRpy(b.pose.translation(), 0.05, -0.02, u(rng));
    b.dims = {4.2, 1.8, 1.5};
    o.model = b;
    o.class_id = 10;
  } else if (shape == 1) {
    Cylinder c;
    c.root = {u(rng), u(rng), -0.5};
    if (rng() % 2) c.axis = Eigen::Vector3d(0.05, -0.1, 1).normalized();
    c.radius = 0.1 + 0.02 * s(rng);
    c.length = 5 * s(rng);
    o.model = c;
    o.class_id = 71;
  } else {
    o.model = Ellipsoid{{u(rng), u(rng), u(rng) / 10}, s(rng), s(rng)};
    o.class_id = static_cast<int>(rng() % 4);
  }
  o.confidence = rng() % 2 ? 1.0 : 0.25 + 0.5 * s(rng) / 3;
  o.num_observations = rng() % 2 ? 1 : static_cast<int>(2 + rng() % 50);
  return o;
}

inline KeyPoseBundle randomBundle(std::mt19937& rng, std::int32_t origin, std::int32_t seq, int num_objects = -1) {
  std::uniform_real_distribution<double> u(-1, 1);
  KeyPoseBundle b;
  b.robot = origin;
  b.seq = seq;
  b.utime = 1700000000000000LL + seq * 1000000LL;
  b.odom_pose = poseFromXyzRpy({100 * u(rng), 100 * u(rng), u(rng)}, 0.02 * u(rng), 0.02 * u(rng), 3 * u(rng));
  b.relative_odom = poseFromXyzRpy({1.4, 0.1 * u(rng), 0.01 * u(rng)}, 0.01 * u(rng), 0.01 * u(rng), 0.2 * u(rng));
  if (rng() % 4) b.odom_sigma << 0.05f, 0.05f, 0.02f, 0.01f, 0.01f, 0.02f;
  const int n = num_objects >= 0 ? num_objects : static_cast<int>(5 + rng() % 16);
  for (int i = 0; i < n; ++i) b.objects.push_back(randomObject(rng, 1000 * origin + static_cast<int>(rng() % 200)));
  return b;
}

// True when b is a copy of a within `tol` (compare with roundTrip() for what receivers get).
inline bool bundlesNear(const KeyPoseBundle& a, const KeyPoseBundle& b, double tol = 1e-5) {
  if (a.robot != b.robot || a.seq != b.seq || a.first != b.first || a.utime != b.utime ||
      a.odom_sigma != b.odom_sigma || a.objects.size() != b.objects.size())
    return false;
  if (!a.odom_pose.isApprox(b.odom_pose, tol) || !a.relative_odom.isApprox(b.relative_odom, tol)) return false;
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const Object &x = a.objects[i], &y = b.objects[i];
    if (x.id != y.id || x.class_id != y.class_id || x.shape() != y.shape() || x.num_observations != y.num_observations ||
        std::abs(x.confidence - y.confidence) > tol || (x.position() - y.position()).norm() > tol ||
        (x.extent() - y.extent()).norm() > tol)
      return false;
  }
  return true;
}

// What a receiver gets back for a bundle: the quantised original (codec.h).
inline KeyPoseBundle roundTrip(const KeyPoseBundle& b) {
  std::string err;
  return *decodeBundle(encodeBundle(b), b.robot, b.seq, &err);
}

// Robot `robot`'s signer with the pair keys derived from `master` (team_keys.h).
inline MessageAuth authOf(std::int32_t robot, const std::vector<std::int32_t>& team,
                          const std::string& master = "team-secret") {
  return MessageAuth(robot, team, derivePairKeys(master, robot, team));
}

inline SyncConfig teamConfig(std::int32_t robot, std::vector<std::int32_t> team, const std::string& master = "team-secret") {
  SyncConfig c;
  c.robot = robot;
  c.team = std::move(team);
  c.pair_keys = derivePairKeys(master, robot, c.team);
  c.heartbeat_period_s = 1.0;
  c.heartbeat_idle_factor = 2.0;
  c.resend_timeout_s = 1.5;
  c.relay_delay_s = 1.5;
  c.peer_timeout_s = 3.0;
  c.ack_delay_s = 0.2;
  c.rate_limit_bytes_per_s = 50000;
  c.burst_bytes = 20000;
  c.thin_observations = false;  // protocol tests compare whole bundles
  return c;
}

}  // namespace slide::team::testing
