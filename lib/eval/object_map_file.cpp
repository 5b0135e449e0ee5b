#include "eval/object_map_file.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>

#include "io/io_error.h"

namespace slide {

namespace {
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

bool parseNumber(const std::string& s, double& v) {
  if (s.empty()) return false;
  try {
    std::size_t used = 0;
    v = std::stod(s, &used);
    return used == s.size() && std::isfinite(v);
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<Shape> parseShape(const std::string& s) {
  if (s == "cuboid") return Shape::Cuboid;
  if (s == "cylinder") return Shape::Cylinder;
  if (s == "ellipsoid") return Shape::Ellipsoid;
  return std::nullopt;
}

const ClassInfo& classForLabel(const ClassTable& classes, double label, const std::string& where) {
  if (label != std::floor(label)) throw IoError(where, "class label " + std::to_string(label) + " is not an integer");
  const int l = static_cast<int>(label);
  if (auto c = classes.fromMapLabel(l)) return classes.at(*c);
  if (const ClassInfo* c = classes.find(l)) return *c;
  throw IoError(where, "label " + std::to_string(l) + " is neither an object-map label nor a class id of the class table");
}

std::vector<Object> readText(std::ifstream& in, const std::string& path, const ClassTable& classes) {
  std::vector<Object> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = path + ": line " + std::to_string(n);
    std::istringstream s(t);
    std::vector<double> v;
    std::string tok;
    while (s >> tok) {
      double x;
      if (!parseNumber(tok, x)) throw IoError(where, "'" + tok + "' is not a number");
      v.push_back(x);
    }
    if (v.size() != 4 && v.size() != 7 && v.size() != 8)
      throw IoError(where, "expected 'label x y z [sx sy sz [yaw]]', got " + std::to_string(v.size()) + " numbers");
    const ClassInfo& cls = classForLabel(classes, v[0], where);
    const Eigen::Vector3d extent = v.size() >= 7 ? Eigen::Vector3d(v[4], v[5], v[6]) : cls.typicalSize();
    if ((extent.array() < 0).any()) throw IoError(where, "negative size");
    Object o = makeObject(cls, cls.shape, {v[1], v[2], v[3]}, extent, v.size() == 8 ? v[7] : 0.0);
    o.id = static_cast<std::int64_t>(out.size());
    out.push_back(o);
  }
  return out;
}

std::vector<Object> readCsv(std::ifstream& in, const std::string& path, const std::string& header,
                            const ClassTable& classes, int default_class) {
  std::map<std::string, std::size_t> col;
  const auto names = splitCsv(header);
  for (std::size_t i = 0; i < names.size(); ++i) col[names[i]] = i;
  auto find = [&](std::initializer_list<const char*> keys) -> std::optional<std::size_t> {
    for (const char* k : keys)
      if (auto it = col.find(k); it != col.end()) return it->second;
    return std::nullopt;
  };
  const auto c_class = find({"class_id", "class"});
  const auto c_x = find({"x"}), c_y = find({"y"}), c_z = find({"z"});
  if ((!c_class && default_class < 0) || !c_x || !c_y)
    throw IoError(path, "CSV header needs columns class_id, x, y (and optionally z)");
  const auto c_id = find({"id"}), c_shape = find({"shape"}), c_yaw = find({"yaw"}), c_conf = find({"confidence"});
  const auto c_sx = find({"size_x", "length"}), c_sy = find({"size_y", "width"}), c_sz = find({"size_z", "height"});
  const auto c_r = find({"radius"});
  const auto c_ax = find({"axis_x"}), c_ay = find({"axis_y"}), c_az = find({"axis_z"});

  std::vector<Object> out;
  std::string line;
  for (int n = 2; std::getline(in, line); ++n) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = path + ": line " + std::to_string(n);
    const auto cells = splitCsv(t);
    auto num = [&](std::optional<std::size_t> c, const char* field) -> std::optional<double> {
      if (!c) return std::nullopt;
      if (*c >= cells.size()) throw IoError(where, std::string("missing field ") + field);
      double v;
      if (!parseNumber(cells[*c], v)) throw IoError(where, std::string("field ") + field + ": '" + cells[*c] + "' is not a number");
      return v;
    };
    const ClassInfo& cls = classForLabel(classes, c_class ? *num(c_class, "class_id") : default_class, where);
    Shape shape = cls.shape;
    if (c_shape) {
      if (*c_shape >= cells.size()) throw IoError(where, "missing field shape");
      const auto s = parseShape(cells[*c_shape]);
      if (!s) throw IoError(where, "field shape: '" + cells[*c_shape] + "' is not cuboid, cylinder or ellipsoid");
      shape = *s;
    }
    Eigen::Vector3d extent = cls.typicalSize();
    if (auto r = num(c_r, "radius")) extent.x() = extent.y() = 2 * *r;
    if (auto v = num(c_sx, "size_x")) extent.x() = *v;
    if (auto v = num(c_sy, "size_y")) extent.y() = *v;
    if (auto v = num(c_sz, "size_z")) extent.z() = *v;
    if ((extent.array() < 0).any()) throw IoError(where, "negative size");
    Object o = makeObject(cls, shape, {*num(c_x, "x"), *num(c_y, "y"), num(c_z, "z").value_or(0.0)}, extent,
                          num(c_yaw, "yaw").value_or(0.0));
    if (auto* cyl = std::get_if<Cylinder>(&o.model); cyl && c_ax && c_ay && c_az) {
      const Eigen::Vector3d axis(*num(c_ax, "axis_x"), *num(c_ay, "axis_y"), *num(c_az, "axis_z"));
      if (axis.norm() < 1e-9) throw IoError(where, "cylinder axis is zero");
      const Eigen::Vector3d centre = o.position();
      cyl->axis = axis.normalized();
      cyl->root = centre - 0.5 * cyl->length * cyl->axis;
    }
    o.id = c_id ? static_cast<std::int64_t>(*num(c_id, "id")) : static_cast<std::int64_t>(out.size());
    o.confidence = num(c_conf, "confidence").value_or(1.0);
    out.push_back(o);
  }
  return out;
}
}  // namespace

Object makeObject(const ClassInfo& cls, Shape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                  double yaw) {
  Object o;
  o.class_id = cls.id;
  switch (shape) {
    case Shape::Cuboid: o.model = Cuboid{poseFromXyzYaw(centre.x(), centre.y(), centre.z(), yaw), extent}; break;
    case Shape::Cylinder: {
      const double len = extent.z();
      o.model = Cylinder{centre - 0.5 * len * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                         0.25 * (extent.x() + extent.y()), len};
      break;
    }
    case Shape::Ellipsoid: o.model = Ellipsoid{centre, 0.25 * (extent.x() + extent.y()), extent.z()}; break;
  }
  return o;
}

std::vector<Object> readObjectMapFile(const std::string& path, const ClassTable& classes, int default_class) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  std::string first;
  std::streampos start = in.tellg();
  // The first non-comment line decides the format: commas mean CSV (that line is its header).
  while (std::getline(in, first)) {
    const std::string t = trim(first);
    if (!t.empty() && t[0] != '#') break;
    start = in.tellg();
  }
  const std::string t = trim(first);
  const bool csv = t.find(',') != std::string::npos;
  if (csv) return readCsv(in, path, t, classes, default_class);
  in.clear();
  in.seekg(start);
  return readText(in, path, classes);
}

void writeObjectMapCsv(const std::string& path, const std::vector<Object>& objects) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,confidence\n"
      << std::setprecision(9);
  for (const Object& o : objects) {
    const Eigen::Vector3d p = o.position(), e = o.extent();
    double yaw = 0, radius = 0;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    if (const auto* c = std::get_if<Cuboid>(&o.model)) yaw = yawOf(c->pose.linear());
    if (const auto* c = std::get_if<Cylinder>(&o.model)) radius = c->radius, axis = c->axis;
    if (const auto* c = std::get_if<Ellipsoid>(&o.model)) radius = c->radius;
    out << o.id << ',' << o.class_id << ',' << shapeName(o.shape()) << ',' << p.x() << ',' << p.y() << ',' << p.z()
        << ',' << yaw << ',' << e.x() << ',' << e.y() << ',' << e.z() << ',' << radius << ',' << axis.x() << ','
        << axis.y() << ',' << axis.z() << ',' << o.confidence << '\n';
  }
  if (!out) throw IoError(path, "write failed");
}

}  // namespace slide
