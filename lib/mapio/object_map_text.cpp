#include "mapio/object_map_text.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.h"

namespace slide {

namespace {
std::runtime_error lineError(const std::string& name, int line, const std::string& what) {
  return std::runtime_error(name + ":" + std::to_string(line) + ": " + what);
}

// strtod accepts "nan" and "inf"; those become non-finite objects, skipped by the caller.
bool parseNumber(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

int classOfLabel(const std::string& token, const std::string& name, int line, const ClassTable& classes) {
  double v = 0;
  if (!parseNumber(token, v) || !std::isfinite(v) || v != std::floor(v))
    throw lineError(name, line, "expected an integer class label, got '" + token + "'");
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw lineError(name, line, "class label '" + token + "' is out of the integer range");
  const int label = static_cast<int>(v);
  if (const auto id = classes.fromMapLabel(label)) return *id;
  if (classes.find(label)) return label;
  throw lineError(name, line, "label " + std::to_string(label) + " is neither a map label nor a class id of the class table");
}
}  // namespace

Object objectFromCentre(int class_id, const Eigen::Vector3d& p, const Eigen::Vector3d& extent,
                        const ClassTable& classes) {
  Object o;
  o.class_id = class_id;
  const ClassInfo* info = classes.find(class_id);
  const Shape shape = info ? info->shape : Shape::Ellipsoid;
  switch (shape) {
    case Shape::Cuboid: {
      Cuboid c;
      c.pose.translation() = p;
      c.dims = extent;
      o.model = c;
      break;
    }
    case Shape::Cylinder: {
      Cylinder c;
      c.radius = 0.25 * (extent.x() + extent.y());
      c.length = extent.z();
      c.root = p - 0.5 * c.length * c.axis;
      o.model = c;
      break;
    }
    case Shape::Ellipsoid:
      o.model = Ellipsoid{p, 0.25 * (extent.x() + extent.y()), extent.z()};
      break;
  }
  return o;
}

ObjectMapText parseObjectMapText(const std::string& text, const std::string& name, const ClassTable& classes) {
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
    if (tok.size() != 4 && tok.size() != 7)
      throw lineError(name, lineno, "expected 'label x y z' or 'label x y z sx sy sz', got " +
                                        std::to_string(tok.size()) + " fields");
    const int cls = classOfLabel(tok[0], name, lineno, classes);
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (std::size_t i = 1; i < tok.size(); ++i)
      if (!parseNumber(tok[i], v[i - 1]))
        throw lineError(name, lineno, "field " + std::to_string(i + 1) + " is not a number: '" + tok[i] + "'");
    const Eigen::Vector3d p(v[0], v[1], v[2]), e(v[3], v[4], v[5]);
    if (!p.allFinite() || !e.allFinite()) {
      out.warnings.push_back(name + ":" + std::to_string(lineno) + ": non-finite number, object skipped");
      continue;
    }
    if ((e.array() < 0).any()) throw lineError(name, lineno, "negative extent");
    Object o = objectFromCentre(cls, p, e, classes);
    o.id = static_cast<std::int64_t>(out.map.size());
    out.map.add(o);
  }
  return out;
}

ObjectMapText readObjectMapText(const std::string& path, const ClassTable& classes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw std::runtime_error(path + ": is a directory, not an object map file");
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open object map for reading");
  std::stringstream buf;
  buf << f.rdbuf();
  if (f.bad()) throw std::runtime_error(path + ": read error");
  return parseObjectMapText(buf.str(), path, classes);
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

}  // namespace slide
