// Encode/decode round trip of every message in lcmtypes/ (package slide), plus truncated
// buffers and the object conversions.
#include <gtest/gtest.h>

#include <vector>

#include "msg/convert.h"
#include "slide/frame_instances_t.hpp"
#include "slide/keypose_bundle_t.hpp"
#include "slide/lidar_scan_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/optimizer_status_t.hpp"
#include "slide/rgbd_frame_t.hpp"
#include "slide/stream_status_t.hpp"
#include "slide/sync_ack_t.hpp"
#include "slide/sync_chunk_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "slide/trajectory_t.hpp"

using namespace slide;

namespace {
template <typename M>
std::vector<uint8_t> encode(const M& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

// Decodes the encoding of m, checks the re-encoding is byte-identical, and that every
// truncated prefix is rejected. Returns the decoded copy.
template <typename M>
M roundTrip(const M& m) {
  const std::vector<uint8_t> buf = encode(m);
  M out;
  EXPECT_EQ(out.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  EXPECT_EQ(encode(out), buf);
  for (std::size_t cut : {std::size_t(0), std::size_t(7), buf.size() / 2, buf.size() - 1}) {
    if (cut >= buf.size()) continue;
    M partial;
    EXPECT_LT(partial.decode(buf.data(), 0, static_cast<int>(cut)), 0) << "prefix of " << cut << " bytes";
  }
  return out;
}

header_t header(int robot, int seq) {
  header_t h;
  h.utime = 1700000000123456LL;
  h.robot = robot;
  h.seq = seq;
  return h;
}

Object someCar() {
  Object o;
  o.id = 42;
  o.class_id = 10;
  o.confidence = 0.9;
  o.num_observations = 3;
  o.model = Cuboid{poseFromXyzYaw(1, 2, 0.8, 0.4), {4.5, 1.8, 1.5}};
  return o;
}
Object someTrunk() {
  Object o;
  o.id = 7;
  o.class_id = 71;
  o.model = Cylinder{{3, 4, -0.5}, Eigen::Vector3d(0.1, 0, 1).normalized(), 0.25, 6};
  return o;
}
Object someChair() {
  Object o;
  o.id = 9;
  o.class_id = 1;
  o.model = Ellipsoid{{-1, 0.5, 0.4}, 0.3, 0.9};
  return o;
}
std::vector<object_t> someObjects() {
  return {msg::toLcm(someCar()), msg::toLcm(someTrunk()), msg::toLcm(someChair())};
}

origin_ranges_t ranges(int origin) {
  origin_ranges_t r;
  r.origin = origin;
  r.ranges = {{0, 10}, {12, 40}};
  r.num_ranges = 2;
  return r;
}
}  // namespace

TEST(Messages, LidarScan) {
  lidar_scan_t m;
  m.header = header(1, 5);
  m.num_points = 3;
  m.xyz = {{1, 2, 3}, {4, 5, 6}, {-7, 8.5f, 0}};
  m.intensity = {0.1f, 0.2f, 0.3f};
  m.has_labels = true;
  m.num_labels = 3;
  m.semantic = {10, 71, 40};
  m.instance = {3, 1, 0};
  const auto out = roundTrip(m);
  EXPECT_EQ(out.xyz[2][1], 8.5f);
  EXPECT_EQ(out.semantic[1], 71);
}

TEST(Messages, RgbdFrame) {
  rgbd_frame_t m;
  m.header = header(2, 9);
  m.intrinsics = {4, 2, 380.0, 380.0, 2.0, 1.0, 0.001};
  m.color_size = 24;
  m.color.assign(24, 200);
  m.depth_size = 16;
  m.depth.assign(16, 3);
  m.mask_size = 16;
  m.instance_mask.assign(16, 0);
  m.instance_mask[2] = 1;
  m.num_instances = 1;
  m.instance_class = {1};
  m.instance_confidence = {0.8f};
  const auto out = roundTrip(m);
  EXPECT_EQ(out.intrinsics.fx, 380.0);
  EXPECT_EQ(out.instance_mask[2], 1);
}

TEST(Messages, OdometryAndStatus) {
  odometry_t o;
  o.header = header(0, 1);
  o.pose = msg::toLcm(poseFromXyzYaw(1, 2, 3, 0.5));
  for (int i = 0; i < 3; ++i) o.linear_velocity[i] = o.angular_velocity[i] = i * 0.5f;
  EXPECT_TRUE(msg::fromLcm(roundTrip(o).pose).isApprox(poseFromXyzYaw(1, 2, 3, 0.5), 1e-12));

  stream_status_t s;
  s.utime = 5;
  s.robot = 1;
  s.state = stream_status_t::FINISHED;
  s.frames_sent = s.frames_total = 100;
  s.source = "/data/forest/robot1";
  EXPECT_EQ(roundTrip(s).source, "/data/forest/robot1");

  optimizer_status_t st;
  st.utime = 1;
  st.robot = 0;
  st.num_keyposes = 100;
  st.num_landmarks = 50;
  st.num_peers_merged = 2;
  st.full_solve = true;
  st.update_ms = 0.7;
  st.final_cost = 12.5;
  st.rejected_inputs = 0;
  EXPECT_EQ(roundTrip(st).num_landmarks, 50);
}

TEST(Messages, FrameInstances) {
  frame_instances_t m;
  m.header = header(0, 3);
  m.odom_pose = msg::toLcm(Pose::Identity());
  object_instance_t inst;
  inst.instance_id = 4;
  inst.class_id = 10;
  inst.confidence = 1;
  inst.num_points = 2;
  inst.xyz = {{1, 1, 1}, {2, 2, 2}};
  inst.num_free = 1;
  inst.free_xy = {{-3, 7}};
  inst.free_z = -1.2f;
  m.instances = {inst, inst};
  m.num_instances = 2;
  EXPECT_EQ(roundTrip(m).instances[1].xyz[1][2], 2.0f);
  EXPECT_EQ(roundTrip(m).instances[1].free_xy[0][1], 7);
}

TEST(Messages, KeyPoseBundleTrajectoryMap) {
  keypose_bundle_t b;
  b.header = header(1, 17);
  b.odom_pose = msg::toLcm(poseFromXyzYaw(10, 0, 0, 0.1));
  b.relative_odom = msg::toLcm(poseFromXyzYaw(1, 0, 0, 0.01));
  for (int i = 0; i < 6; ++i) b.odom_sigma[i] = 0.01f * i;
  b.objects = someObjects();
  b.num_objects = 3;
  EXPECT_EQ(roundTrip(b).objects[1].num_cylinder, 1);

  trajectory_t t;
  t.utime = 1;
  t.robot = 2;
  t.frame_robot = 0;
  t.num_poses = 2;
  t.keypose_seq = {0, 1};
  t.pose_utime = {100, 200};
  t.poses = {msg::toLcm(Pose::Identity()), msg::toLcm(poseFromXyzYaw(1, 0, 0, 0))};
  EXPECT_EQ(roundTrip(t).pose_utime[1], 200);

  object_map_t map;
  map.utime = 1;
  map.robot = 0;
  map.frame_robot = 0;
  map.objects = someObjects();
  map.num_objects = 3;
  EXPECT_EQ(roundTrip(map).objects[2].num_ellipsoid, 1);
}

TEST(Messages, KeyPoseBundleConvertsBothWaysAndDropsModellessObjects) {
  KeyPoseBundle b;
  b.robot = 2;
  b.seq = 7;
  b.utime = 123456;
  b.odom_pose = poseFromXyzYaw(10, 2, 0.5, 0.3);
  b.relative_odom = poseFromXyzYaw(1, 0, 0, 0.01);
  b.odom_sigma << 0.01f, 0.02f, 0.03f, 0.001f, 0.002f, 0.003f;
  Object car;
  car.id = 4;
  car.class_id = 10;
  car.model = Cuboid{poseFromXyzYaw(3, 1, 0.8, 0.2), {4.5, 1.8, 1.5}};
  Object trunk;
  trunk.id = 5;
  trunk.class_id = 71;
  trunk.model = Cylinder{{1, 2, 0}, Eigen::Vector3d::UnitZ(), 0.2, 6};
  b.objects = {car, trunk};
  keypose_bundle_t m = roundTrip(msg::toLcm(b));
  EXPECT_EQ(m.header.robot, 2);
  EXPECT_EQ(m.num_objects, 2);
  std::vector<std::string> dropped;
  const KeyPoseBundle back = msg::fromLcm(m, &dropped);
  EXPECT_TRUE(dropped.empty());
  EXPECT_EQ(back.robot, 2);
  EXPECT_EQ(back.seq, 7);
  EXPECT_EQ(back.utime, 123456);
  EXPECT_TRUE(back.odom_pose.isApprox(b.odom_pose, 1e-12));
  EXPECT_TRUE(back.relative_odom.isApprox(b.relative_odom, 1e-12));
  EXPECT_EQ(back.odom_sigma, b.odom_sigma);  // float values travel exactly
  ASSERT_EQ(back.objects.size(), 2u);
  EXPECT_EQ(back.objects[1].id, 5);
  EXPECT_EQ(back.objects[1].shape(), Shape::Cylinder);
  // An object without a model is left out and named; the rest of the bundle stays.
  m.objects[0].num_cuboid = 0;
  m.objects[0].cuboid.clear();
  const KeyPoseBundle rest = msg::fromLcm(m, &dropped);
  ASSERT_EQ(rest.objects.size(), 1u);
  EXPECT_EQ(rest.objects[0].id, 5);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_NE(dropped[0].find("4"), std::string::npos) << dropped[0];
}

TEST(Messages, LoopClosure) {
  loop_closure_t m;
  m.utime = 1;
  m.robot_a = 0;
  m.robot_b = 2;
  m.keypose_a = m.keypose_b = -1;
  m.method = loop_closure_t::SLIDEGRAPH;
  m.x = 1;
  m.y = 2;
  m.z = 0.1;
  m.yaw = 0.5;
  m.score = 12;
  m.residual_rms = 0.05;
  m.num_inliers = 2;
  m.inliers_a = {1, 2};
  m.inliers_b = {5, 6};
  EXPECT_EQ(roundTrip(m).inliers_b[1], 6);
}

TEST(Messages, PeerSync) {
  sync_heartbeat_t h;
  h.sender = 1;
  h.counter = 99;
  h.held = {ranges(0), ranges(1)};
  h.num_origins = 2;
  h.mac_size = 16;
  for (int i = 0; i < 16; ++i) h.mac.push_back(static_cast<uint8_t>(i * 7));
  EXPECT_EQ(roundTrip(h).held[1].ranges[1].last, 40);

  sync_chunk_t c;
  c.sender = 1;
  c.receiver = -1;
  c.counter = 100;
  c.kind = sync_chunk_t::BUNDLE;
  c.origin = 2;
  c.seq = 30;
  c.chunk_index = 0;
  c.num_chunks = 1;
  c.data = {1, 2, 3, 4, 5};
  c.size = 5;
  c.mac_size = 16;
  c.mac.assign(16, 0xAB);
  EXPECT_EQ(roundTrip(c).data[4], 5);

  sync_ack_t a;
  a.sender = 2;
  a.receiver = 1;
  a.counter = 7;
  a.acked = {ranges(2)};
  a.num_origins = 1;
  a.mac_size = 8;
  a.mac.assign(8, 1);
  EXPECT_EQ(roundTrip(a).acked[0].origin, 2);
}

TEST(Messages, ObjectConversionRoundTrip) {
  for (const Object& o : {someCar(), someTrunk(), someChair()}) {
    const Object back = msg::fromLcm(roundTrip(msg::toLcm(o)));
    EXPECT_EQ(back.id, o.id);
    EXPECT_EQ(back.class_id, o.class_id);
    EXPECT_EQ(back.shape(), o.shape());
    EXPECT_TRUE(back.position().isApprox(o.position(), 1e-5));
    EXPECT_TRUE(back.extent().isApprox(o.extent(), 1e-5));
  }
  object_t empty = msg::toLcm(someCar());
  empty.num_cuboid = 0;
  empty.cuboid.clear();
  EXPECT_THROW(msg::fromLcm(empty), std::invalid_argument);
}

TEST(Messages, ABoxReadTwoWaysTravelsAsTwoCuboids) {
  Object car = someCar();
  car.other_reading = Cuboid{poseFromXyzYaw(1, 2, 0.8, 1.2), {4.5, 1.8, 1.5}};
  const object_t m = roundTrip(msg::toLcm(car));
  EXPECT_EQ(m.num_cuboid, 2);
  const Object back = msg::fromLcm(m);
  ASSERT_TRUE(back.other_reading.has_value());
  EXPECT_TRUE(back.other_reading->pose.isApprox(car.other_reading->pose, 1e-5));
  EXPECT_TRUE(back.other_reading->dims.isApprox(car.other_reading->dims, 1e-6));
  EXPECT_FALSE(msg::fromLcm(msg::toLcm(someCar())).other_reading.has_value());
  // Three boxes, or two beside a cylinder, are no object.
  object_t three = m;
  three.cuboid.push_back(m.cuboid[0]);
  three.num_cuboid = 3;
  EXPECT_THROW(msg::fromLcm(three), std::invalid_argument);
  object_t mixed = msg::toLcm(someTrunk());
  mixed.cuboid = m.cuboid;
  mixed.num_cuboid = 2;
  EXPECT_THROW(msg::fromLcm(mixed), std::invalid_argument);
}
