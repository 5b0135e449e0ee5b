// The viewer's logic without LCM, HTTP or a browser: scene deltas and snapshots, thinning, the
// replay clock, LCM logs read incrementally and through corruption, the node's defence against
// hostile messages, and a log player jumping back in time.
#include <gtest/gtest.h>

#include <filesystem>

#include "log_player.h"
#include "viewer_log_fixture.h"
#include "viewer_node.h"

using namespace slide;
using namespace slide::viewer_test;
namespace fs = std::filesystem;

namespace {
std::string tempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("slide_viewer_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}
template <class M>
bool feed(ViewerNode& node, int view, const std::string& channel, const M& m, double t = 0) {
  const auto bytes = msg::encodeLcm(m);
  return node.onRobotBus(view, channel, bytes.data(), bytes.size(), t);
}
std::size_t setCount(const nlohmann::json& d, int view) {
  const std::string v = std::to_string(view);
  if (!d["views"].contains(v) || !d["views"][v].contains("objects")) return 0;
  return d["views"][v]["objects"]["set"].size();
}
}  // namespace

TEST(ViewerScene, DeltaCarriesOnlyWhatChangedAndRemovals) {
  viewer::Scene s;
  s.setObjectMap(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)}, 1.0);
  const nlohmann::json first = s.delta(0, 0);
  EXPECT_TRUE(first["reset"].get<bool>());
  EXPECT_EQ(setCount(first, 0), 3u);
  const auto e = s.epoch(), v1 = s.version();
  // The same map again (re-published by the optimizer): nothing new.
  s.setObjectMap(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)}, 2.0);
  EXPECT_EQ(s.version(), v1);
  // Moved by 1 mm: below the centimetre the page draws, still nothing.
  s.setObjectMap(0, {car(1, 10.001, 5), trunk(2, 20, -5), bush(3, 30, 5)}, 2.5);
  EXPECT_EQ(s.version(), v1);
  // The car moves 0.5 m and the bush is gone: one object set, one removed.
  s.setObjectMap(0, {car(1, 10.5, 5), trunk(2, 20, -5)}, 3.0);
  const nlohmann::json d = s.delta(e, v1);
  EXPECT_FALSE(d["reset"].get<bool>());
  ASSERT_EQ(setCount(d, 0), 1u);
  EXPECT_EQ(d["views"]["0"]["objects"]["set"][0][0], 1);
  EXPECT_DOUBLE_EQ(d["views"]["0"]["objects"]["set"][0][3].get<double>(), 10.5);
  EXPECT_EQ(d["views"]["0"]["objects"]["del"], nlohmann::json::array({3}));
  EXPECT_EQ(s.delta(e, s.version())["views"].size(), 0u);
}

TEST(ViewerScene, ShapesRowsAreCuboidCylinderEllipsoid) {
  viewer::Scene s;
  s.setObjectMap(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)}, 1.0);
  const auto rows = s.delta(0, 0)["views"]["0"]["objects"]["set"];
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].size(), 13u);  // id, class, shape, centre 3, quaternion 4, dims 3
  EXPECT_EQ(rows[0][1], 10);
  EXPECT_EQ(rows[0][2], 0);
  EXPECT_DOUBLE_EQ(rows[0][10].get<double>(), 4.5);
  EXPECT_EQ(rows[1].size(), 11u);  // root 3, axis 3, radius, length
  EXPECT_EQ(rows[1][2], 1);
  EXPECT_DOUBLE_EQ(rows[1][9].get<double>(), 0.3);
  EXPECT_EQ(rows[2].size(), 8u);  // centroid 3, radius, height
  EXPECT_EQ(rows[2][2], 2);
}

TEST(ViewerScene, ClientTooFarBehindOrFromAnOldEpochGetsASnapshot) {
  viewer::SceneLimits lim;
  lim.max_tombstones = 4;
  viewer::Scene s(lim);
  std::vector<Object> many;
  for (int i = 0; i < 10; ++i) many.push_back(bush(i, i, 0));
  s.setObjectMap(0, many, 1.0);
  const auto e = s.epoch(), v = s.version();
  s.setObjectMap(0, {bush(0, 0, 0)}, 2.0);  // 9 removals: more than the tombstones kept
  const nlohmann::json d = s.delta(e, v);
  EXPECT_TRUE(d["reset"].get<bool>());
  EXPECT_EQ(setCount(d, 0), 1u);
  s.reset();
  EXPECT_TRUE(s.delta(e, s.version())["reset"].get<bool>());
  EXPECT_EQ(s.objectCount(0), 0u);
}

TEST(ViewerScene, TrajectoriesThinnedAndResentOnlyWhenMoved) {
  viewer::SceneLimits lim;
  lim.max_trajectory_points = 100;
  viewer::Scene s(lim);
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i < 1000; ++i) path.emplace_back(0.1 * i, 0, 0);
  s.setTrajectory(0, 1, path, 1.0);
  const auto d = s.delta(0, 0);
  const auto& flat = d["views"]["0"]["trajectories"]["1"];
  ASSERT_EQ(flat.size(), 300u);
  EXPECT_DOUBLE_EQ(flat[297].get<double>(), 99.9);  // the newest pose is always kept
  const auto v = s.version();
  for (auto& p : path) p.y() += 0.01;  // 1 cm: below the tolerance
  s.setTrajectory(0, 1, path, 2.0);
  EXPECT_EQ(s.version(), v);
  path.back().y() += 0.5;
  s.setTrajectory(0, 1, path, 3.0);
  EXPECT_GT(s.version(), v);
}

TEST(ViewerScene, TeamLinksExpireAndRateIsAveraged) {
  viewer::Scene s;
  for (int i = 0; i < 10; ++i) s.noteTeamMessage(0, 1, 500, 100.0 + 0.5 * i);
  auto team = s.delta(0, 0)["team"]["0"];
  EXPECT_EQ(team["linked"], nlohmann::json::array({1}));
  EXPECT_DOUBLE_EQ(team["bytes_per_s"].get<double>(), 1000.0);  // 5000 B over the 5 s window
  s.tick(120.0);
  team = s.delta(0, 0)["team"]["0"];
  EXPECT_TRUE(team["linked"].empty());
  EXPECT_DOUBLE_EQ(team["bytes_per_s"].get<double>(), 0.0);
}

TEST(ViewerScene, InstancesThinnedToTheBudget) {
  std::vector<viewer::InstanceView> in(3);
  for (int i = 0; i < 1000; ++i) in[0].points.emplace_back(i, 0, 0);
  for (int i = 0; i < 100; ++i) in[1].points.emplace_back(i, 1, 0);
  in[2].points.emplace_back(NAN, 0, 0);
  const auto out = viewer::thinInstances(in, 110);
  std::size_t n = 0;
  for (const auto& i : out) n += i.points.size();
  EXPECT_LE(n, 110u);
  ASSERT_EQ(out.size(), 2u);  // the all-NaN instance is left out
  EXPECT_EQ(out[0].points.size(), 99u);  // 1000 of 1101 points: 99 of 110
  EXPECT_EQ(out[1].points.size(), 9u);
  std::vector<viewer::InstanceView> many(500, viewer::InstanceView{0, {Eigen::Vector3f(1, 2, 3)}});
  EXPECT_EQ(viewer::thinInstances(many, 50).size(), 50u);
}

TEST(ViewerReplayClock, PauseSpeedSeekAndLive) {
  viewer::ReplayClock c(100.0, 200.0, false, 0.0);
  EXPECT_DOUBLE_EQ(c.position(10.0), 110.0);
  c.setSpeed(4.0, 10.0);
  EXPECT_DOUBLE_EQ(c.position(12.0), 118.0);
  c.pause(12.0);
  EXPECT_DOUBLE_EQ(c.position(50.0), 118.0);
  c.seek(150.0, 50.0);
  EXPECT_DOUBLE_EQ(c.position(60.0), 150.0);  // still paused
  c.play(60.0);
  EXPECT_DOUBLE_EQ(c.position(61.0), 154.0);
  EXPECT_DOUBLE_EQ(c.position(1000.0), 200.0);  // clamped at the end
  c.setSpeed(NAN, 61.0);
  EXPECT_DOUBLE_EQ(c.speed(), 4.0);
  c.setSpeed(1e9, 61.0);
  EXPECT_DOUBLE_EQ(c.speed(), viewer::ReplayClock::kMaxSpeed);
  c.goLive();
  c.extend(300.0);
  EXPECT_DOUBLE_EQ(c.position(61.0), 300.0);
  c.seek(-1e9, 70.0);
  EXPECT_FALSE(c.live());
  EXPECT_DOUBLE_EQ(c.position(70.0), 100.0);
}

TEST(ViewerLcmLog, ReadsWhatIsWrittenFollowsGrowthAndSkipsCorruption) {
  const std::string dir = tempDir("log");
  const std::string path = dir + "/robot0.lcmlog";
  {
    LogWriter w(path);
    w.write("OBJECT_MAP", mapMsg(0, {car(1, 1, 1)}), 10);
    w.write("SCAN", optimizerMsg(0, 1), 20);
  }
  io::LcmLogReader r(path);
  io::LcmLogEvent ev;
  ASSERT_TRUE(r.next(ev, [](const std::string& c) { return c != "SCAN"; }));
  EXPECT_EQ(ev.channel, "OBJECT_MAP");
  EXPECT_EQ(ev.utime, 10);
  EXPECT_FALSE(r.next(ev, [](const std::string& c) { return c != "SCAN"; }));
  EXPECT_EQ(r.counts().skipped, 1u);
  // A half-written event: not returned until it is whole.
  const auto whole = msg::encodeLcm(optimizerMsg(0, 2));
  {
    std::FILE* f = std::fopen(path.c_str(), "ab");
    std::vector<std::uint8_t> buf;
    std::FILE* mem = std::fopen((dir + "/one").c_str(), "wb");
    io::writeLcmLogEvent(mem, {7, 30, "OPTIMIZER_STATUS", whole});
    std::fclose(mem);
    std::FILE* in = std::fopen((dir + "/one").c_str(), "rb");
    buf.resize(fs::file_size(dir + "/one"));
    ASSERT_EQ(std::fread(buf.data(), 1, buf.size(), in), buf.size());
    std::fclose(in);
    std::fwrite(buf.data(), 1, 10, f);
    std::fflush(f);
    EXPECT_FALSE(r.next(ev));
    std::fwrite(buf.data() + 10, 1, buf.size() - 10, f);
    // Then garbage, then a good event: the garbage is skipped and counted.
    const char junk[] = "not an event at all, just bytes";
    std::fwrite(junk, 1, sizeof junk, f);
    std::fclose(f);
  }
  {
    LogWriter w(path, "ab");
    w.write("TRAJECTORY", trajectoryMsg(0, 0, 3, 0, 0), 40);
  }
  ASSERT_TRUE(r.next(ev));
  EXPECT_EQ(ev.channel, "OPTIMIZER_STATUS");
  EXPECT_EQ(ev.data, whole);
  ASSERT_TRUE(r.next(ev));
  EXPECT_EQ(ev.channel, "TRAJECTORY");
  EXPECT_GE(r.counts().corrupt_bytes, sizeof("not an event at all, just bytes"));
  EXPECT_THROW(io::LcmLogReader(dir + "/absent.lcmlog"), std::runtime_error);
  fs::remove_all(dir);
}

TEST(ViewerNode, DrawsARunsMessages) {
  viewer::Scene scene;
  ViewerNode node(scene);
  EXPECT_TRUE(feed(node, 0, "TRAJECTORY", trajectoryMsg(0, 0, 20, 0, 0)));
  EXPECT_TRUE(feed(node, 0, "TRAJECTORY", trajectoryMsg(1, 0, 10, 0, 10)));
  EXPECT_TRUE(feed(node, 0, "KEYPOSE_BUNDLE", bundleMsg(0, 19, 38, 0)));
  EXPECT_TRUE(feed(node, 0, "INSTANCES_PREVIEW", instancesMsg(0, 1000)));
  EXPECT_TRUE(feed(node, 0, "OBJECT_MAP", mapMsg(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)})));
  EXPECT_TRUE(feed(node, 0, "LOOP_CLOSURE", loopMsg(0, 1, {1, 2})));
  EXPECT_TRUE(feed(node, 0, "OPTIMIZER_STATUS", optimizerMsg(0, 3)));
  EXPECT_TRUE(feed(node, 0, "SENSOR_STATUS", sensorMsg(0, 40, 100)));
  const auto d = scene.delta(0, 0)["views"]["0"];
  EXPECT_EQ(d["objects"]["set"].size(), 3u);
  EXPECT_EQ(d["trajectories"]["0"].size(), 60u);
  EXPECT_EQ(d["trajectories"]["1"].size(), 30u);
  EXPECT_EQ(d["keypose"]["seq"], 19);
  EXPECT_DOUBLE_EQ(d["keypose"]["p"][0].get<double>(), 38.0);
  EXPECT_EQ(d["instances"]["p"].size(), 3u * 200u);  // thinned from 1000 points
  EXPECT_EQ(d["loops"][0]["inliers_a"], nlohmann::json::array({1, 2}));
  EXPECT_EQ(d["optimizer"]["landmarks"], 3);
  EXPECT_EQ(d["sensor"]["sent"], 40);
  EXPECT_EQ(node.dropped(), 0u);
}

TEST(ViewerNode, KeyPoseAndInstancesFollowTheOptimizedTrajectory) {
  viewer::Scene scene;
  ViewerNode node(scene);
  // Odometry says key pose 19 is at x 38; the optimizer moved it to (38, 2): later key poses
  // and instances are drawn with that correction.
  trajectory_t t = trajectoryMsg(0, 0, 20, 0, 0);
  t.poses[19] = msg::toLcm(poseFromXyzYaw(38, 2, 0, 0));
  EXPECT_TRUE(feed(node, 0, "KEYPOSE_BUNDLE", bundleMsg(0, 19, 38, 0)));
  EXPECT_TRUE(feed(node, 0, "TRAJECTORY", t));
  EXPECT_TRUE(feed(node, 0, "KEYPOSE_BUNDLE", bundleMsg(0, 20, 40, 0)));
  const auto d = scene.delta(0, 0)["views"]["0"];
  EXPECT_DOUBLE_EQ(d["keypose"]["p"][0].get<double>(), 40.0);
  EXPECT_DOUBLE_EQ(d["keypose"]["p"][1].get<double>(), 2.0);
}

TEST(ViewerNode, HostileMessagesAreDroppedAndCountedNeverThrown) {
  viewer::Scene scene;
  ViewerNode node(scene);
  // Truncated, padded and random bytes on every channel the viewer draws.
  const auto good = msg::encodeLcm(mapMsg(0, {car(1, 10, 5)}));
  for (const char* ch : {"OBJECT_MAP", "TRAJECTORY", "KEYPOSE_BUNDLE", "INSTANCES_PREVIEW", "LOOP_CLOSURE",
                         "OPTIMIZER_STATUS", "SENSOR_STATUS"}) {
    EXPECT_FALSE(node.onRobotBus(0, ch, good.data(), good.size() / 2, 0)) << ch;
    std::vector<std::uint8_t> noise(4096);
    for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<std::uint8_t>(i * 7919 + 13);
    EXPECT_FALSE(node.onRobotBus(0, ch, noise.data(), noise.size(), 0)) << ch;
  }
  for (const char* ch : {"TEAM_HEARTBEAT", "TEAM_CHUNK", "TEAM_ACK"})
    EXPECT_FALSE(node.onTeamBus(0, ch, good.data(), 3, 0)) << ch;
  auto padded = good;
  padded.push_back(0);
  EXPECT_FALSE(node.onRobotBus(0, "OBJECT_MAP", padded.data(), padded.size(), 0));
  // Absurd numbers inside well-formed messages.
  object_map_t bad = mapMsg(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)});
  bad.objects[1].cylinder[0].radius = NAN;
  bad.objects[2].ellipsoid[0].centroid[0] = 1e12f;
  bad.objects[0].num_cuboid = 0;  // no model at all
  bad.objects[0].cuboid.clear();
  EXPECT_TRUE(feed(node, 0, "OBJECT_MAP", bad));
  EXPECT_EQ(node.droppedObjects(), 3u);
  EXPECT_EQ(scene.objectCount(0), 0u);
  trajectory_t nan_traj = trajectoryMsg(0, 0, 5, 0, 0);
  nan_traj.poses[2].position[1] = NAN;
  EXPECT_FALSE(feed(node, 0, "TRAJECTORY", nan_traj));
  trajectory_t zero_q = trajectoryMsg(0, 0, 5, 0, 0);
  zero_q.poses[0].orientation[0] = 0;
  EXPECT_FALSE(feed(node, 0, "TRAJECTORY", zero_q));
  loop_closure_t lc = loopMsg(0, 1, {1});
  lc.yaw = INFINITY;
  EXPECT_FALSE(feed(node, 0, "LOOP_CLOSURE", lc));
  optimizer_status_t os = optimizerMsg(0, 1);
  os.update_ms = NAN;
  EXPECT_FALSE(feed(node, 0, "OPTIMIZER_STATUS", os));
  EXPECT_FALSE(feed(node, 0, "OBJECT_MAP", mapMsg(1, {car(1, 1, 1)})));  // robot 1's map on robot 0's bus
  EXPECT_GE(node.dropped(), 7u * 2 + 3 + 1 + 5);
  EXPECT_NE(node.dropSummary().find("OBJECT_MAP"), std::string::npos);
  // After all that, a good message still draws.
  EXPECT_TRUE(feed(node, 0, "OBJECT_MAP", mapMsg(0, {car(1, 10, 5)})));
  EXPECT_EQ(scene.objectCount(0), 1u);
}

TEST(ViewerLogPlayer, RunFolderReplayedSeekBackResetsTheScene) {
  const std::string dir = tempDir("player");
  fs::create_directories(dir + "/logs");
  const std::int64_t t0 = 1700000000000000LL;
  {
    LogWriter w(dir + "/logs/robot0.lcmlog");
    writeRobotRun(w, t0);
    w.write("OBJECT_MAP", mapMsg(0, {car(1, 10, 5)}), t0 + 5000000);  // 5 s in: two objects gone
    LogWriter team(dir + "/logs/team0.lcmlog");
    for (int i = 0; i < 4; ++i) team.write("TEAM_HEARTBEAT", heartbeatMsg(1, i), t0 + i * 1000000);
  }
  const auto sources = logSourcesOf(dir);
  ASSERT_EQ(sources.size(), 2u);
  EXPECT_TRUE(sources[1].team);
  EXPECT_THROW(logSourcesOf(dir + "/nothing"), std::runtime_error);
  EXPECT_EQ(logSourcesOf("3=" + dir + "/x.lcmlog")[0].robot, 3);
  viewer::Scene scene;
  ViewerNode node(scene);
  LogPlayer player(sources, node, scene, false, 0.0);
  EXPECT_EQ(player.events(), 8u + 1u + 4u);
  player.clock().pause(0.0);
  player.clock().seek(t0 * 1e-6 + 1.0, 0.0);
  player.advance(0.0);
  EXPECT_EQ(scene.objectCount(0), 3u);
  EXPECT_EQ(scene.delta(0, 0)["team"]["0"]["linked"], nlohmann::json::array({1}));
  player.clock().seek(t0 * 1e-6 + 6.0, 0.0);
  player.advance(0.0);
  EXPECT_EQ(scene.objectCount(0), 1u);
  const auto epoch = scene.epoch();
  player.clock().seek(t0 * 1e-6 + 0.5, 0.0);  // back: replayed from the start into a new epoch
  player.advance(0.0);
  EXPECT_GT(scene.epoch(), epoch);
  EXPECT_EQ(scene.objectCount(0), 3u);
  fs::remove_all(dir);
}
