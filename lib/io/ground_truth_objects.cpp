#include "io/ground_truth_objects.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>

#include "io/io_error.h"
#include "io/numbers.h"
#include "io/object_map_text.h"

namespace slide::io {

namespace {
const char* kHeader = "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy";

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::optional<Shape> parseShape(const std::string& s) {
  if (s == "cuboid") return Shape::Cuboid;
  if (s == "cylinder") return Shape::Cylinder;
  if (s == "ellipsoid") return Shape::Ellipsoid;
  return std::nullopt;
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

std::vector<Object> readObjectsCsv(const std::string& path, const ClassTable* classes, int default_class,
                                   const std::vector<std::string>& extra, std::vector<std::vector<double>>* extra_values) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  std::string line, header;
  int n = 0;
  while (header.empty() && std::getline(in, line)) {
    ++n;
    if (const std::string t = trim(line); !t.empty() && t[0] != '#') header = t;
  }
  if (header.empty()) throw IoError(path, "no header line naming the columns");
  std::map<std::string, std::size_t> col;
  const auto names = splitCsv(header);
  for (std::size_t i = 0; i < names.size(); ++i) col.emplace(names[i], i);
  auto find = [&](std::initializer_list<const char*> keys) -> std::optional<std::size_t> {
    for (const char* k : keys)
      if (auto it = col.find(k); it != col.end()) return it->second;
    return std::nullopt;
  };
  const auto c_class = find({"class_id", "class"});
  const auto c_x = find({"x"}), c_y = find({"y"}), c_z = find({"z"});
  if ((!c_class && default_class < 0) || !c_x || !c_y)
    throw IoError(path, "line " + std::to_string(n) + ": the CSV header needs columns class_id, x, y (and optionally z)");
  const auto c_id = find({"id"}), c_shape = find({"shape"}), c_yaw = find({"yaw"}), c_conf = find({"confidence"});
  if (!classes && !c_shape) throw IoError(path, "line " + std::to_string(n) + ": the CSV header needs a shape column");
  const auto c_sx = find({"size_x", "length"}), c_sy = find({"size_y", "width"}), c_sz = find({"size_z", "height"});
  const auto c_r = find({"radius"});
  const auto c_ax = find({"axis_x"}), c_ay = find({"axis_y"}), c_az = find({"axis_z"});
  std::vector<std::size_t> c_extra;
  for (const std::string& e : extra) {
    const auto it = col.find(e);
    if (it == col.end()) throw IoError(path, "line " + std::to_string(n) + ": the CSV header lacks column " + e);
    c_extra.push_back(it->second);
  }

  std::vector<Object> out;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = "line " + std::to_string(n);
    const auto cells = splitCsv(t);
    auto cell = [&](std::size_t c, const std::string& field) -> const std::string& {
      if (c >= cells.size()) throw IoError(path, where + ": missing field " + field);
      return cells[c];
    };
    auto number = [&](std::size_t c, const std::string& field) {
      const std::optional<double> v = parseNumber(cell(c, field));
      if (!v || !std::isfinite(*v)) throw IoError(path, where + ": field " + field + ": '" + cells[c] + "' is not a number");
      return *v;
    };
    auto num = [&](std::optional<std::size_t> c, const char* field) -> std::optional<double> {
      if (!c) return std::nullopt;
      return number(*c, field);
    };
    const double label = c_class ? number(*c_class, "class_id") : default_class;
    if (label != std::floor(label) || std::abs(label) > 1e9)
      throw IoError(path, where + ": class label " + std::to_string(label) + " is not an integer");
    const ClassInfo* cls = classes ? classOfMapLabel(*classes, static_cast<int>(label)) : nullptr;
    if (classes && !cls)
      throw IoError(path, where + ": label " + std::to_string(static_cast<int>(label)) +
                              " is neither an object-map label nor a class id of the class table");
    Shape shape = cls ? cls->shape : Shape::Ellipsoid;
    if (c_shape) {
      const auto s = parseShape(cell(*c_shape, "shape"));
      if (!s) throw IoError(path, where + ": field shape: '" + cells[*c_shape] + "' is not cuboid, cylinder or ellipsoid");
      shape = *s;
    }
    Eigen::Vector3d extent = cls ? cls->typicalSize() : Eigen::Vector3d::Zero();
    if (auto v = num(c_sx, "size_x")) extent.x() = *v;
    if (auto v = num(c_sy, "size_y")) extent.y() = *v;
    if (auto v = num(c_sz, "size_z")) extent.z() = *v;
    if (auto r = num(c_r, "radius"); r && shape != Shape::Cuboid) extent.x() = extent.y() = 2 * *r;
    if ((extent.array() < 0).any()) throw IoError(path, where + ": negative size");
    const Eigen::Vector3d centre(*num(c_x, "x"), *num(c_y, "y"), num(c_z, "z").value_or(0.0));
    Object o = objectFromExtent(cls ? cls->id : static_cast<int>(label), shape, centre, extent,
                                num(c_yaw, "yaw").value_or(0.0));
    if (auto* cyl = std::get_if<Cylinder>(&o.model); cyl && c_ax && c_ay && c_az) {
      const Eigen::Vector3d axis(*num(c_ax, "axis_x"), *num(c_ay, "axis_y"), *num(c_az, "axis_z"));
      if (axis.norm() < 1e-9) throw IoError(path, where + ": cylinder axis is zero");
      cyl->axis = axis.normalized();
      cyl->root = centre - 0.5 * cyl->length * cyl->axis;
    }
    o.id = c_id ? static_cast<std::int64_t>(number(*c_id, "id")) : static_cast<std::int64_t>(out.size());
    o.confidence = num(c_conf, "confidence").value_or(1.0);
    if (extra_values) {
      std::vector<double>& row = extra_values->emplace_back();
      for (std::size_t k = 0; k < extra.size(); ++k) row.push_back(number(c_extra[k], extra[k]));
    }
    out.push_back(o);
  }
  return out;
}

std::vector<GroundTruthObject> readGroundTruthObjects(const std::string& path) {
  std::vector<std::vector<double>> extra;
  const std::vector<Object> objects = readObjectsCsv(path, nullptr, -1, {"semantic", "vx", "vy"}, &extra);
  std::vector<GroundTruthObject> out(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    out[i].object = objects[i];
    out[i].semantic = static_cast<uint16_t>(extra[i][0]);
    out[i].velocity = {extra[i][1], extra[i][2]};
  }
  return out;
}

}  // namespace slide::io
