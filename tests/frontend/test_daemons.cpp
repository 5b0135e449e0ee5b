// slide-segmenter and slide-tracker as processes on a private LCM bus: inside a new network
// namespace (unshare -n; loopback up with a multicast route, so nothing leaves this test), a
// hand-made labelled dataset (a robot driving past trunks and a parked car) is replayed as
// ODOM + SCAN messages, with bad frames mixed in; key-pose bundles must come out with seq
// 0, 1, 2, ... and tracked objects, and both daemons must survive the bad input.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>
#include <thread>

#include "msg/frontend_convert.h"
#include "msg/convert.h"
#include "slide/odometry_t.hpp"
#include "drive_by.h"
#include "synthetic_scene.h"

extern char** environ;

using namespace slide;

namespace {
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

pid_t spawn(const std::string& exe, std::vector<std::string> args) {
  args.insert(args.begin(), exe);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  return pid;
}

// Terminates the daemon when the test ends, however it ends.
struct Daemon {
  pid_t pid = -1;
  ~Daemon() {
    if (pid > 0 && kill(pid, SIGTERM) == 0) waitpid(pid, nullptr, 0);
  }
  // SIGTERM and the exit status (true: clean exit 0).
  bool stop() {
    int status = 0;
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    pid = -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }
};

bool alive(pid_t pid) {
  int status = 0;
  return waitpid(pid, &status, WNOHANG) == 0;
}

struct Collector {
  std::vector<keypose_bundle_t> bundles;
  int instances = 0;
  void onBundle(const lcm::ReceiveBuffer*, const std::string&, const keypose_bundle_t* m) { bundles.push_back(*m); }
  void onInstances(const lcm::ReceiveBuffer*, const std::string&, const frame_instances_t*) { ++instances; }
};

void pump(lcm::LCM& lcm, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) lcm.handleTimeout(20);
}
}  // namespace

TEST(FrontendDaemons, ReplayedDatasetGivesKeyPoseBundles) {
  ASSERT_EQ(unshare(CLONE_NEWNET), 0) << "unshare(CLONE_NEWNET) failed (tests run as root)";
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);

  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/";
  const std::vector<std::string> common{"--robot", "0", "--lcm-url", kUrl, "--log-level", "warn"};
  Daemon seg{spawn(bin + "slide-segmenter", common)}, trk{spawn(bin + "slide-tracker", common)};
  ASSERT_GT(seg.pid, 0);
  ASSERT_GT(trk.pid, 0);

  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  Collector got;
  lcm.subscribe("KEYPOSE_BUNDLE", &Collector::onBundle, &got);
  lcm.subscribe("INSTANCES", &Collector::onInstances, &got);
  pump(lcm, 1.0);  // daemons subscribe

  const std::vector<synth::SceneObject> scene{{71, {6, 4, 0}, 0.25, 6.0}, {71, {12, -4, 0}, 0.35, 6.0},
                                              {10, {9, 5, 0}, 0, 0, 0.1}};
  const int frames = 24;
  int expected = 0;  // instance messages: one per usable scan
  for (int k = 0; k < frames; ++k) {
    const Pose T = slide::testing::driveByPose(k);
    const header_t h = slide::testing::driveByHeader(k);
    const odometry_t odom = slide::testing::driveByOdometry(k);
    lcm.publish("ODOM", &odom);
    if (k == 5) {  // bad input: an empty scan and one with non-finite points
      lidar_scan_t empty = msg::toLcm(io::LabelledScan{}, h);
      lcm.publish("SCAN", &empty);
    } else {
      io::LabelledScan scan = synth::syntheticScan(scene, T, 0.08, k + 1, 0.01, 0.6);
      if (k == 8) scan.xyz[3] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
      const lidar_scan_t m = msg::toLcm(scan, h);
      lcm.publish("SCAN", &m);
    }
    if (k == 10) {  // an RGBD frame whose images do not match its intrinsics
      rgbd_frame_t bad{};
      bad.header = h;
      bad.intrinsics.width = 640;
      bad.intrinsics.height = 480;
      bad.intrinsics.fx = bad.intrinsics.fy = 500;
      bad.depth_size = 10;
      bad.depth.assign(10, 0);
      lcm.publish("RGBD", &bad);
    }
    // Lock step: the next frame goes out once this one's instances are back (a loaded
    // machine would otherwise queue scans until the kernel drops datagrams).
    expected += k != 5;
    for (int i = 0; i < 150 && got.instances < expected; ++i) pump(lcm, 0.02);
  }
  // One more pose after the last scan (a driver keeps sending odometry).
  odometry_t last{};
  last.header.utime = 1000000 + frames * 100000;
  last.pose = msg::toLcm(poseFromXyzYaw(0.4 * frames, 0, 1.5, 0));
  lcm.publish("ODOM", &last);
  for (int i = 0; i < 200 && got.instances < expected; ++i) pump(lcm, 0.05);
  pump(lcm, 0.5);

  EXPECT_TRUE(alive(seg.pid)) << "segmenter died";
  EXPECT_TRUE(alive(trk.pid)) << "tracker died";
  EXPECT_TRUE(seg.stop()) << "segmenter did not exit cleanly";
  EXPECT_TRUE(trk.stop()) << "tracker did not exit cleanly";

  // One instance message per usable scan; the empty scan and the bad RGBD frame give none.
  EXPECT_EQ(got.instances, frames - 1);
  ASSERT_GE(got.bundles.size(), 6u);  // ~9.2 m driven, a key pose per metre
  std::map<std::int64_t, int> seen_ids;
  for (std::size_t i = 0; i < got.bundles.size(); ++i) {
    const auto& b = got.bundles[i];
    EXPECT_EQ(b.header.seq, static_cast<int>(i));
    EXPECT_EQ(b.header.robot, 0);
    for (const auto& o : b.objects) ++seen_ids[o.id];
  }
  const auto& final_bundle = got.bundles.back();
  EXPECT_GE(final_bundle.num_objects, 2);
  // Objects keep their track ids across bundles.
  int repeated = 0;
  for (const auto& [id, n] : seen_ids) repeated += n >= 3;
  EXPECT_GE(repeated, 2);
  for (const auto& o : final_bundle.objects) {
    const Object obj = msg::fromLcm(o);
    const Eigen::Vector3d world = msg::fromLcm(final_bundle.odom_pose) * obj.position();
    double best = 1e9;
    for (const auto& s : scene) best = std::min(best, (world.head<2>() - s.center.head<2>()).norm());
    EXPECT_LT(best, obj.class_id == 10 ? 1.0 : 0.3) << "object " << obj.id << " of class " << obj.class_id;
  }
}

// lidar_mode learned on the bus: the segmenter runs the project's model (config/frontend.yaml)
// on every scan and answers each with its instances; the scans' own labels are not used.
TEST(FrontendDaemons, LearnedModeAnswersEveryScan) {
  ASSERT_EQ(unshare(CLONE_NEWNET), 0) << "unshare(CLONE_NEWNET) failed (tests run as root)";
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);
  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/";
  Daemon seg{spawn(bin + "slide-segmenter", {"--robot", "0", "--lcm-url", kUrl, "--log-level", "warn", "--mode", "learned"})};
  ASSERT_GT(seg.pid, 0);
  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  Collector got;
  lcm.subscribe("INSTANCES", &Collector::onInstances, &got);
  pump(lcm, 1.5);  // the daemon loads its model and subscribes
  const std::vector<synth::SceneObject> scene{{71, {6, 4, 0}, 0.25, 6.0}, {10, {9, 5, 0}, 0, 0, 0.1}};
  const int frames = 4;
  for (int k = 0; k < frames; ++k) {
    const odometry_t odom = slide::testing::driveByOdometry(k);
    lcm.publish("ODOM", &odom);
    const lidar_scan_t m =
        msg::toLcm(synth::syntheticScan(scene, slide::testing::driveByPose(k), 0.08, k + 1, 0.01, 0.6),
                   slide::testing::driveByHeader(k));
    lcm.publish("SCAN", &m);
    for (int i = 0; i < 250 && got.instances < k; ++i) pump(lcm, 0.02);
  }
  const odometry_t last = slide::testing::driveByOdometry(frames);
  lcm.publish("ODOM", &last);
  for (int i = 0; i < 250 && got.instances < frames; ++i) pump(lcm, 0.02);
  EXPECT_EQ(got.instances, frames);
  EXPECT_TRUE(alive(seg.pid)) << "segmenter died";
  EXPECT_TRUE(seg.stop()) << "segmenter did not exit cleanly";
}

// A missing model stops the daemon at start, naming the file.
TEST(FrontendDaemons, LearnedModeWithoutItsModelFailsAtStart) {
  ASSERT_EQ(unshare(CLONE_NEWNET), 0) << "unshare(CLONE_NEWNET) failed (tests run as root)";
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);
  const std::string config = ::testing::TempDir() + "/frontend_no_model.yaml";
  std::ofstream(config) << "segmenter:\n  lidar_mode: learned\n  learned:\n    model: models/nowhere.yaml\n";
  const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-segmenter --config " + config + " --lcm-url '" + kUrl +
                          "' 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = pclose(p);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("nowhere.yaml"), std::string::npos) << out;
}
