// PCD folders: scans in PCL's format (written here by hand in its ASCII and binary layouts),
// times from file names or times.txt, odometry interpolated at the scans' times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "io/io_error.h"
#include "io/robot_dataset.h"
#include "io/tum_trajectory.h"

namespace fs = std::filesystem;
using namespace slide;

namespace {
void writeAsciiPcd(const fs::path& p, int n) {
  std::ofstream o(p);
  o << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
    << "COUNT 1 1 1 1\nWIDTH " << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA ascii\n";
  for (int i = 0; i < n; ++i) o << (i == 1 ? "nan" : std::to_string(i + 1.0)) << " 2 3 " << 10 * i << "\n";
}

void writeBinaryPcd(const fs::path& p, int n) {
  std::ofstream o(p, std::ios::binary);
  o << "VERSION 0.7\nFIELDS x y z intensity ring\nSIZE 4 4 4 4 2\nTYPE F F F F U\nCOUNT 1 1 1 1 1\nWIDTH " << n
    << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA binary\n";
  for (int i = 0; i < n; ++i) {
    const float v[4] = {float(i + 1), 2, 3, 5};
    const uint16_t ring = 7;
    o.write(reinterpret_cast<const char*>(v), sizeof(v));
    o.write(reinterpret_cast<const char*>(&ring), sizeof(ring));
  }
}
}  // namespace

TEST(PcdFolder, ScansTimedByFileNameWithInterpolatedOdometry) {
  const fs::path dir = fs::temp_directory_path() / ("slide_pcd_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeAsciiPcd(dir / "1700000000.100000.pcd", 4);
  writeBinaryPcd(dir / "1700000000.200000.pcd", 5);
  writeAsciiPcd(dir / "1700000009.000000.pcd", 2);  // after the odometry ends
  std::vector<StampedPose> odom;
  for (int k = 0; k <= 30; ++k) odom.push_back({1700000000.0 + 0.01 * k + 0.003, poseFromXyzYaw(0.03 * k + 0.009, 0, 0, 0)});
  io::writeTum((dir / "odom.txt").string(), odom);
  const io::RobotDataset d = io::openRobotDataset(dir.string());
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.dropped.outside_span, 1u);
  EXPECT_NEAR(d.odometry[1].pose.translation().x(), 3.0 * 0.2, 1e-5);  // x = 3 t
  const io::LabelledScan a = d.scan(0), b = d.scan(1);
  EXPECT_EQ(a.size(), 3u);  // the NaN point skipped
  EXPECT_EQ(a.intensity[2], 30.f);
  EXPECT_EQ(b.size(), 5u);
  EXPECT_EQ(b.xyz[4].x(), 5.f);
  // A broken scan names its file; a times.txt of the wrong length names itself.
  std::ofstream(dir / "1700000000.200000.pcd") << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\n";
  try {
    d.scan(1);
    ADD_FAILURE() << "no IoError";
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("1700000000.200000.pcd"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "times.txt") << "0.1\n";
  EXPECT_THROW(io::openRobotDataset(dir.string()), io::IoError);
  fs::remove_all(dir);
}
