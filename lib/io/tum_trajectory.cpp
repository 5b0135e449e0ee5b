#include "io/tum_trajectory.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "io/atomic_file.h"
#include "io/io_error.h"

namespace slide::io {

std::vector<StampedPose> readTum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  std::vector<StampedPose> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream s(line);
    double v[8];
    for (double& x : v)
      if (!(s >> x) || !std::isfinite(x))
        throw IoError(path, "line " + std::to_string(n) + ": expected 8 numbers (t tx ty tz qx qy qz qw)");
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-2) throw IoError(path, "line " + std::to_string(n) + ": quaternion is not unit length");
    if (!out.empty() && v[0] < out.back().t)
      throw IoError(path, "line " + std::to_string(n) + ": timestamp goes backwards");
    out.push_back({v[0], poseFromPositionQuaternion({v[1], v[2], v[3]}, q)});
  }
  return out;
}

void writeTum(const std::string& path, const std::vector<StampedPose>& trajectory) {
  std::ostringstream out;
  out << std::fixed;
  for (const StampedPose& p : trajectory) {
    const Eigen::Vector3d t = p.pose.translation();
    const Eigen::Quaterniond q(p.pose.linear());
    out << std::setprecision(6) << p.t << std::setprecision(9) << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' '
        << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
  writeFileAtomically(path, out.str());
}

}  // namespace slide::io
