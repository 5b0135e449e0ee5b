#include "io/ground_truth_objects.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "io/io_error.h"

namespace slide {

namespace {
const char* kHeader = "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy";

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream s(line);
  while (std::getline(s, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double toNumber(const std::string& text, const std::string& path, int line, const char* column) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size() && text.find_first_not_of(" \t\r", used) != std::string::npos) throw std::invalid_argument("");
    if (!std::isfinite(v)) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw IoError(path, "line " + std::to_string(line) + ": column " + column + ": expected a number, got '" + text + "'");
  }
}
}  // namespace

Object GroundTruthObject::at(double t) const {
  if (!moving()) return object;
  return transformObject(Pose(Eigen::Translation3d(velocity.x() * t, velocity.y() * t, 0.0)), object);
}

void writeGroundTruthObjects(const std::string& path, const std::vector<GroundTruthObject>& objects) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << kHeader << '\n' << std::setprecision(6) << std::fixed;
  for (const GroundTruthObject& g : objects) {
    const Object& o = g.object;
    const Eigen::Vector3d c = o.position();
    const Eigen::Vector3d e = o.extent();
    double yaw = 0, radius = 0;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    if (const auto* cub = std::get_if<Cuboid>(&o.model)) yaw = yawOf(cub->pose.linear());
    if (const auto* cyl = std::get_if<Cylinder>(&o.model)) radius = cyl->radius, axis = cyl->axis;
    if (const auto* ell = std::get_if<Ellipsoid>(&o.model)) radius = ell->radius;
    out << o.id << ',' << o.class_id << ',' << shapeName(o.shape()) << ',' << c.x() << ',' << c.y() << ',' << c.z() << ','
        << yaw << ',' << e.x() << ',' << e.y() << ',' << e.z() << ',' << radius << ',' << axis.x() << ',' << axis.y()
        << ',' << axis.z() << ',' << g.semantic << ',' << g.velocity.x() << ',' << g.velocity.y() << '\n';
  }
  if (!out) throw IoError(path, "write failed");
}

std::vector<GroundTruthObject> readGroundTruthObjects(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  std::string line;
  if (!std::getline(in, line)) throw IoError(path, "empty file: expected the header line");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kHeader) throw IoError(path, "line 1: unexpected header; expected '" + std::string(kHeader) + "'");
  static const char* cols[] = {"id", "class_id", "shape", "x", "y", "z", "yaw", "length", "width",
                               "height", "radius", "axis_x", "axis_y", "axis_z", "semantic", "vx", "vy"};
  std::vector<GroundTruthObject> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> f = splitCsv(line);
    if (f.size() != 17)
      throw IoError(path, "line " + std::to_string(n) + ": expected 17 columns, got " + std::to_string(f.size()));
    double v[17] = {};
    for (int i = 0; i < 17; ++i)
      if (i != 2) v[i] = toNumber(f[i], path, n, cols[i]);
    GroundTruthObject g;
    g.object.id = static_cast<std::int64_t>(v[0]);
    g.object.class_id = static_cast<int>(v[1]);
    g.semantic = static_cast<uint16_t>(v[14]);
    g.velocity = {v[15], v[16]};
    const Eigen::Vector3d c(v[3], v[4], v[5]);
    std::string shape = f[2];
    while (!shape.empty() && (shape.back() == ' ' || shape.back() == '\r')) shape.pop_back();
    if (shape == "cuboid") {
      g.object.model = Cuboid{poseFromXyzYaw(c.x(), c.y(), c.z(), v[6]), {v[7], v[8], v[9]}};
    } else if (shape == "cylinder") {
      Eigen::Vector3d axis(v[11], v[12], v[13]);
      if (axis.norm() < 1e-9) throw IoError(path, "line " + std::to_string(n) + ": cylinder axis is zero");
      axis.normalize();
      g.object.model = Cylinder{c - 0.5 * v[9] * axis, axis, v[10], v[9]};
    } else if (shape == "ellipsoid") {
      g.object.model = Ellipsoid{c, v[10], v[9]};
    } else {
      throw IoError(path, "line " + std::to_string(n) + ": unknown shape '" + shape + "' (cuboid|cylinder|ellipsoid)");
    }
    out.push_back(g);
  }
  return out;
}

}  // namespace slide
