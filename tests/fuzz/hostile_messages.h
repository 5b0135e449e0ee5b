#pragma once
// Valid sample messages of every type a daemon subscribes to, and seeded hostile variants of
// their bytes for the fuzz tests: every length field (and every other position) overwritten
// with hostile lengths (-1, 2^31-1, 2^29, 2^28, INT32_MIN, 0x7fff, ...), random bit flips,
// truncations, and absurd values. The 8-byte fingerprint is kept, so a variant reaches the
// generated decoder and is not refused as a wrong type.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/discovery_t.hpp"
#include "procman_lcm/orders_t.hpp"
#include "slide/frame_instances_t.hpp"
#include "slide/keypose_bundle_t.hpp"
#include "slide/lidar_scan_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/rgbd_frame_t.hpp"
#include "slide/sync_ack_t.hpp"
#include "slide/sync_chunk_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide::fuzz {

using Bytes = std::vector<std::uint8_t>;

template <class M>
Bytes encode(const M& m) {
  Bytes b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

inline pose3_t pose(double x, double y) {
  pose3_t p;
  p.position[0] = x, p.position[1] = y, p.position[2] = 0;
  p.orientation[0] = 1, p.orientation[1] = p.orientation[2] = p.orientation[3] = 0;
  return p;
}
inline header_t header(int robot, int seq) {
  header_t h;
  h.utime = 1000000 + seq * 100000LL, h.robot = robot, h.seq = seq;
  return h;
}

inline object_t object(std::int64_t id, double x, double y) {
  object_t o{};
  o.id = id, o.class_id = 1, o.confidence = 0.9f, o.num_observations = 3;
  o.num_cuboid = 0, o.num_ellipsoid = 0, o.num_cylinder = 1;
  cylinder_t c{};
  c.root[0] = static_cast<float>(x), c.root[1] = static_cast<float>(y), c.root[2] = 0;
  c.axis[2] = 1, c.radius = 0.3f, c.length = 2.f;
  o.cylinder.push_back(c);
  return o;
}

inline keypose_bundle_t bundle(int robot, int seq) {
  keypose_bundle_t m;
  m.header = header(robot, seq);
  m.odom_pose = pose(seq * 1.0, 0);
  m.relative_odom = pose(seq ? 1.0 : 0.0, 0);
  for (int i = 0; i < 6; ++i) m.odom_sigma[i] = 0.05f;
  m.num_objects = 2;
  m.objects = {object(1, 3, 2), object(2, 5, -2)};
  return m;
}

inline object_map_t objectMap(int robot) {
  object_map_t m;
  m.utime = 1000000, m.robot = robot, m.frame_robot = robot;
  for (int i = 0; i < 4; ++i) m.objects.push_back(object(i, 3.0 * i, i % 2 ? 2.0 : -2.0));
  m.num_objects = static_cast<std::int32_t>(m.objects.size());
  return m;
}

inline trajectory_t trajectory(int robot) {
  trajectory_t m;
  m.utime = 1000000, m.robot = robot, m.frame_robot = robot, m.num_poses = 3;
  for (int i = 0; i < 3; ++i) {
    m.keypose_seq.push_back(i);
    m.pose_utime.push_back(1000000 + i);
    m.poses.push_back(pose(i, 0));
  }
  return m;
}

inline loop_closure_t loopClosure(int robot) {
  loop_closure_t m{};
  m.utime = 1000000, m.robot_a = robot, m.robot_b = robot, m.keypose_a = 0, m.keypose_b = 1;
  m.method = loop_closure_t::SLIDEGRAPH, m.x = 1, m.yaw = 0.01, m.score = 5, m.residual_rms = 0.1;
  m.num_inliers = 2, m.inliers_a = {1, 2}, m.inliers_b = {1, 2};
  return m;
}

inline lidar_scan_t scan(int robot, int seq) {
  lidar_scan_t m;
  m.header = header(robot, seq);
  m.num_points = 64;
  for (int i = 0; i < m.num_points; ++i) {
    m.xyz.push_back({5.f + 0.01f * i, 0.1f * (i % 8), 0.2f * (i / 8)});
    m.intensity.push_back(0.5f);
  }
  m.has_labels = true, m.num_labels = m.num_points;
  m.semantic.assign(64, 1);
  m.instance.assign(64, 1);
  return m;
}

inline rgbd_frame_t rgbd(int robot, int seq) {
  rgbd_frame_t m{};
  m.header = header(robot, seq);
  m.intrinsics.width = 4, m.intrinsics.height = 2, m.intrinsics.fx = m.intrinsics.fy = 2;
  m.intrinsics.cx = 2, m.intrinsics.cy = 1, m.intrinsics.depth_scale = 1000;
  m.color_size = 24, m.color.assign(24, 100);
  m.depth_size = 16, m.depth.assign(16, 3);
  m.mask_size = 8, m.instance_mask.assign(8, 1);
  m.num_instances = 2, m.instance_class = {0, 1}, m.instance_confidence = {0.f, 0.9f};
  return m;
}

inline odometry_t odometry(int robot, int seq) {
  odometry_t m{};
  m.header = header(robot, seq);
  m.pose = pose(seq * 0.5, 0);
  return m;
}

inline frame_instances_t instances(int robot, int seq) {
  frame_instances_t m;
  m.header = header(robot, seq);
  m.odom_pose = pose(seq * 0.5, 0);
  object_instance_t o;
  o.instance_id = 1, o.class_id = 1, o.confidence = 0.9f, o.num_points = 20;
  o.num_free = 2, o.free_xy = {{40, 0}, {41, 1}}, o.free_z = -1.0f;
  for (int i = 0; i < 20; ++i) o.xyz.push_back({4.f + 0.02f * (i % 5), 0.02f * (i / 5), 0.1f * i});
  m.instances = {o};
  m.num_instances = 1;
  return m;
}

inline sync_heartbeat_t heartbeat(int sender) {
  sync_heartbeat_t m{};
  m.sender = static_cast<std::int16_t>(sender), m.counter = 5, m.num_origins = 1;
  origin_ranges_t r;
  r.origin = static_cast<std::int16_t>(sender), r.num_ranges = 1;
  r.ranges = {seq_range_t{0, 3}};
  m.held = {r};
  return m;
}
inline sync_chunk_t chunk(int sender) {
  sync_chunk_t m{};
  m.sender = static_cast<std::int16_t>(sender), m.receiver = -1, m.counter = 6, m.kind = sync_chunk_t::BUNDLE;
  m.origin = static_cast<std::int16_t>(sender), m.seq = 0, m.chunk_index = 0, m.num_chunks = 1;
  m.size = 40, m.data.assign(40, 7);
  return m;
}
inline sync_ack_t ack(int sender, int receiver) {
  sync_ack_t m{};
  m.sender = static_cast<std::int16_t>(sender), m.receiver = static_cast<std::int16_t>(receiver), m.counter = 7;
  m.num_origins = 1;
  origin_ranges_t r;
  r.origin = static_cast<std::int16_t>(receiver), r.num_ranges = 2;
  r.ranges = {seq_range_t{0, 3}, seq_range_t{5, 9}};
  m.acked = {r};
  return m;
}

inline procman_lcm::orders_t orders(const std::string& deputy) {
  procman_lcm::orders_t m{};
  m.utime = 1, m.deputy_id = deputy, m.sheriff_id = "fuzz-sheriff", m.ncmds = 1;
  procman_lcm::cmd_desired_t c{};
  c.cmd.exec_str = "/bin/true", c.cmd.command_id = "probe", c.cmd.group = "g";
  c.cmd.auto_respawn = false, c.cmd.stop_signal = 15, c.cmd.stop_time_allowed = 1;
  c.desired_runid = 0, c.force_quit = false;
  m.cmds = {c};
  return m;
}
inline procman_lcm::discovery_t discovery() {
  procman_lcm::discovery_t m{};
  m.utime = 1, m.transmitter_id = "fuzz", m.nonce = 42;
  return m;
}
inline procman_lcm::deputy_info_t deputyInfo(const std::string& deputy) {
  procman_lcm::deputy_info_t m{};
  m.utime = 1, m.deputy_id = deputy, m.cpu_load = 0.1f, m.ncmds = 0;
  return m;
}

// Hostile variants of `valid`, after its 8-byte fingerprint. `positions`: every position
// when 0, else that many seeded random ones; every variant is one write of a hostile length
// (int32, int16 or int8) at one position, one truncation, or `flips` random byte flips.
struct Mutator {
  explicit Mutator(std::uint32_t seed) : rng(seed) {}
  std::mt19937 rng;

  std::vector<Bytes> hostileLengths(const Bytes& valid, std::size_t positions = 0) {
    static const std::int64_t k32[] = {-1, 0x7fffffff, 1 << 29, 1 << 28, 1 << 30, INT32_MIN, 0x00ffffff};
    static const std::int64_t k16[] = {-1, 0x7fff, -32768};
    static const std::int64_t k8[] = {-1, 127, -128};
    std::vector<std::size_t> at;
    for (std::size_t p = 8; p < valid.size(); ++p) at.push_back(p);
    if (positions && positions < at.size()) {
      std::shuffle(at.begin(), at.end(), rng);
      at.resize(positions);
    }
    std::vector<Bytes> out;
    for (std::size_t p : at) {
      for (std::int64_t v : k32) out.push_back(put(valid, p, v, 4));
      for (std::int64_t v : k16) out.push_back(put(valid, p, v, 2));
      for (std::int64_t v : k8) out.push_back(put(valid, p, v, 1));
    }
    return out;
  }
  Bytes flipped(const Bytes& valid, int flips) {
    Bytes b = valid;
    std::uniform_int_distribution<std::size_t> pos(8, b.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < flips; ++i) b[pos(rng)] ^= static_cast<std::uint8_t>(1 + byte(rng) % 255);
    return b;
  }
  Bytes truncated(const Bytes& valid) {
    std::uniform_int_distribution<std::size_t> len(0, valid.size() - 1);
    return Bytes(valid.begin(), valid.begin() + static_cast<long>(len(rng)));
  }
  // Absurd values: 8 bytes of a double (NaN, inf, 1e300, 3e9) or 4 of a float (NaN, inf,
  // 3e38) written at a random position.
  Bytes absurd(const Bytes& valid) {
    static const double kD[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                1e300, 3e9, -1e18};
    static const float kF[] = {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity(),
                               3e38f, 2e9f};
    Bytes b = valid;
    std::uniform_int_distribution<std::size_t> pos(8, b.size() > 16 ? b.size() - 8 : 8);
    std::uniform_int_distribution<int> pick(0, 8);
    const int k = pick(rng);
    std::uint64_t bits = 0;
    std::size_t n = 8;
    if (k < 5) {
      std::memcpy(&bits, &kD[k], 8);
    } else {
      std::uint32_t f;
      std::memcpy(&f, &kF[k - 5], 4);
      bits = f;
      n = 4;
    }
    const std::size_t p = std::min(pos(rng), b.size() - n);
    for (std::size_t i = 0; i < n; ++i) b[p + i] = static_cast<std::uint8_t>(bits >> (8 * (n - 1 - i)));
    return b;
  }

 private:
  static Bytes put(const Bytes& valid, std::size_t p, std::int64_t v, std::size_t n) {
    Bytes b = valid;
    const auto u = static_cast<std::uint64_t>(v);
    for (std::size_t i = 0; i < n && p + i < b.size(); ++i) b[p + i] = static_cast<std::uint8_t>(u >> (8 * (n - 1 - i)));
    return b;
  }
};

}  // namespace slide::fuzz
