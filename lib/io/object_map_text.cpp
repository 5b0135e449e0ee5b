#include "io/object_map_text.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "io/atomic_file.h"
#include "io/ground_truth_objects.h"
#include "io/io_error.h"
#include "io/numbers.h"

namespace slide::io {

namespace {
IoError lineError(const std::string& name, int line, const std::string& what) {
  return IoError(name, "line " + std::to_string(line) + ": " + what);
}

const ClassInfo& classOfLabel(const std::string& token, const std::string& name, int line, const ClassTable& classes) {
  const std::optional<double> v = parseNumber(token);
  if (!v || !std::isfinite(*v) || *v != std::floor(*v))
    throw lineError(name, line, "expected an integer class label, got '" + token + "'");
  if (*v < std::numeric_limits<int>::min() || *v > std::numeric_limits<int>::max())
    throw lineError(name, line, "class label '" + token + "' is out of the integer range");
  const int label = static_cast<int>(*v);
  if (const ClassInfo* c = classOfMapLabel(classes, label)) return *c;
  throw lineError(name, line, "label " + std::to_string(label) + " is neither a map label nor a class id of the class table");
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}
}  // namespace

Object objectFromExtent(int class_id, Shape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                        double yaw) {
  Object o;
  o.class_id = class_id;
  switch (shape) {
    case Shape::Cuboid: o.model = Cuboid{poseFromXyzYaw(centre.x(), centre.y(), centre.z(), yaw), extent}; break;
    case Shape::Cylinder: {
      const double length = extent.z();
      o.model = Cylinder{centre - 0.5 * length * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                         0.25 * (extent.x() + extent.y()), length};
      break;
    }
    case Shape::Ellipsoid: o.model = Ellipsoid{centre, 0.25 * (extent.x() + extent.y()), extent.z()}; break;
  }
  return o;
}

const ClassInfo* classOfMapLabel(const ClassTable& classes, int label) {
  if (const auto id = classes.fromMapLabel(label)) return classes.find(*id);
  return classes.find(label);
}

Object objectFromCentre(int class_id, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                        const ClassTable& classes, double yaw) {
  const ClassInfo* info = classes.find(class_id);
  return objectFromExtent(class_id, info ? info->shape : Shape::Ellipsoid, centre, extent, yaw);
}

ObjectMapText parseObjectMapText(const std::string& text, const std::string& name, const ClassTable& classes,
                                 MissingSize missing) {
  ObjectMapText out;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream fields(line);
    std::vector<std::string> tok;
    for (std::string t; fields >> t;) tok.push_back(t);
    if (tok.empty() || tok[0][0] == '#') continue;
    if (tok.size() != 4 && tok.size() != 7 && tok.size() != 8)
      throw lineError(name, lineno, "expected 'label x y z [sx sy sz [yaw]]', got " + std::to_string(tok.size()) + " fields");
    const ClassInfo& cls = classOfLabel(tok[0], name, lineno, classes);
    double v[7] = {0, 0, 0, 0, 0, 0, 0};
    for (std::size_t i = 1; i < tok.size(); ++i) {
      const std::optional<double> x = parseNumber(tok[i]);
      if (!x) throw lineError(name, lineno, "field " + std::to_string(i + 1) + " is not a number: '" + tok[i] + "'");
      v[i - 1] = *x;
    }
    const Eigen::Vector3d p(v[0], v[1], v[2]);
    const Eigen::Vector3d e = tok.size() >= 7 || missing == MissingSize::Zero ? Eigen::Vector3d(v[3], v[4], v[5])
                                                                              : cls.typicalSize();
    if (!p.allFinite() || !e.allFinite() || !std::isfinite(v[6])) {
      out.warnings.push_back(name + ": line " + std::to_string(lineno) + ": non-finite number, object skipped");
      continue;
    }
    if ((e.array() < 0).any()) throw lineError(name, lineno, "negative size");
    Object o = objectFromExtent(cls.id, cls.shape, p, e, v[6]);
    o.id = static_cast<std::int64_t>(out.map.size());
    out.map.add(o);
  }
  return out;
}

ObjectMapText readObjectMapText(const std::string& path, const ClassTable& classes, MissingSize missing) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path, "is a directory, not an object map file");
  std::ifstream f(path);
  if (!f) throw IoError(path, "cannot open object map for reading");
  std::stringstream buf;
  buf << f.rdbuf();
  if (f.bad()) throw IoError(path, "read error");
  return parseObjectMapText(buf.str(), path, classes, missing);
}

std::string formatObjectMapText(const ObjectMap& map, const ClassTable& classes) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (const Object& o : map.objects()) {
    const ClassInfo* info = classes.find(o.class_id);
    const int label = info && !info->map_labels.empty() ? info->map_labels.front() : o.class_id;
    const Eigen::Vector3d p = o.position(), e = o.extent();
    out << label << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << e.x() << ' ' << e.y() << ' ' << e.z() << '\n';
  }
  return out.str();
}

void writeObjectMapText(const std::string& path, const ObjectMap& map, const ClassTable& classes) {
  writeFileAtomically(path, formatObjectMapText(map, classes));
}

std::vector<Object> readObjectMapFile(const std::string& path, const ClassTable& classes, int default_class) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  // The first line that is not blank or a comment decides: commas mean CSV.
  for (std::string line; std::getline(in, line);) {
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    if (t.find(',') != std::string::npos) return readObjectsCsv(path, &classes, default_class);
    break;
  }
  const ObjectMapText text = readObjectMapText(path, classes, MissingSize::ClassTypical);
  if (!text.warnings.empty()) throw IoError(path, "an object has a non-finite number (" + text.warnings.front() + ")");
  return text.map.objects();
}

}  // namespace slide::io
