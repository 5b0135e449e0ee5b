// slide-segment end to end: a text scan, a PCD scan, a real scan scored against its labels,
// and bad files (clear errors naming the file, exit code 1).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace std::string_literals;
namespace fs = std::filesystem;

class SegmentTool : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slide_segment_tool_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  int run(const std::string& args) const {
    const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-segment " + args + " > '" + path("out.txt") + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string output() const {
    std::ifstream in(path("out.txt"));
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  // Ground plus one pole at (6, 2), radius 0.08 m, 5 m tall, near half sampled.
  void writePoleScene(std::ostream& out, const char* sep) const {
    for (double x = -10; x <= 10; x += 0.25)
      for (double y = -10; y <= 10; y += 0.25) out << x << sep << y << sep << -1.5 << "\n";
    for (double z = 0; z < 5; z += 0.05)
      for (double a = -1.4; a <= 1.4; a += 0.15) {
        const double f = std::atan2(-2.0, -6.0) + a;
        out << 6 + 0.08 * std::cos(f) << sep << 2 + 0.08 * std::sin(f) << sep << z - 1.5 << sep << 0.3 << "\n";
      }
  }
  fs::path dir_;
};

TEST_F(SegmentTool, TextScanGivesThePoleAsJsonAndAPlot) {
  {
    std::ofstream out(path("scan.txt"));
    writePoleScene(out, " ");
  }
  ASSERT_EQ(run(path("scan.txt") + " --plot " + path("scan.png") + " --json " + path("scan.json")), 0) << output();
  const std::string out = output();
  EXPECT_NE(out.find("\"mode\": \"geometric\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"shape\": \"cylinder\", \"position\": [6.0"), std::string::npos) << out;
  EXPECT_GT(fs::file_size(path("scan.png")), 1000u);
  EXPECT_GT(fs::file_size(path("scan.json")), 100u);
}

TEST_F(SegmentTool, PcdScanIsReadThroughPcl) {
  std::ostringstream pts;
  writePoleScene(pts, " ");
  std::istringstream lines(pts.str());
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) {
    std::istringstream l(line);
    double x, y, z;
    l >> x >> y >> z;
    rows.push_back(std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z));
  }
  {
    std::ofstream out(path("scan.pcd"));
    out << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << rows.size()
        << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << rows.size() << "\nDATA ascii\n";
    for (const auto& r : rows) out << r << "\n";
  }
  ASSERT_EQ(run(path("scan.pcd")), 0) << output();
  EXPECT_NE(output().find("\"shape\": \"cylinder\", \"position\": [6.0"), std::string::npos) << output();
}

TEST_F(SegmentTool, RealScanScoredAgainstItsLabels) {
  const std::string d = SLIDE_DATA_DIR + "/semantickitti/sequences/08/"s;
  ASSERT_EQ(run(d + "velodyne/000720.bin --labels " + d + "labels/000720.label"), 0) << output();
  const std::string out = output();
  EXPECT_NE(out.find("\"cars\": {\"targets\": 1, \"found\": 1"), std::string::npos) << out;
  EXPECT_NE(out.find("\"trunks_poles\": {\"targets\": 8"), std::string::npos) << out;
  EXPECT_NE(out.find("\"verdict\": \"matched\""), std::string::npos);
}

TEST_F(SegmentTool, BadFilesGiveErrorsNamingThem) {
  EXPECT_EQ(run(path("missing.bin")), 1);
  EXPECT_NE(output().find("missing.bin"), std::string::npos) << output();
  {
    std::ofstream out(path("short.bin"), std::ios::binary);
    out << "0123456789";  // not a multiple of 16 bytes
  }
  EXPECT_EQ(run(path("short.bin")), 1);
  EXPECT_NE(output().find("short.bin"), std::string::npos) << output();
  {
    std::ofstream out(path("bad.txt"));
    out << "1 2 3\n4 five 6\n";
  }
  EXPECT_EQ(run(path("bad.txt")), 1);
  EXPECT_NE(output().find("bad.txt"), std::string::npos) << output();
  {
    std::ofstream out(path("bad.pcd"));
    out << "# .PCD v0.7\nFIELDS a b\nthis is not a point cloud\n";
  }
  EXPECT_EQ(run(path("bad.pcd")), 1);
  EXPECT_NE(output().find("bad.pcd"), std::string::npos) << output();
  {
    std::ofstream out(path("ok.txt"));
    writePoleScene(out, " ");
  }
  EXPECT_EQ(run(path("ok.txt") + " --mode labelled"), 1);
  EXPECT_NE(output().find("--labels"), std::string::npos) << output();
  EXPECT_EQ(run(path("ok.txt") + " --labels " + path("short.bin")), 1);
  EXPECT_NE(output().find("short.bin"), std::string::npos) << output();
}
