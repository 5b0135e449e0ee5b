#include "objects/class_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "config/config.h"

namespace slide {

namespace {
Shape parseShape(const ConfigNode& c) {
  const std::string s = c.get<std::string>("shape");
  if (s == "cuboid") return Shape::Cuboid;
  if (s == "cylinder") return Shape::Cylinder;
  if (s == "ellipsoid") return Shape::Ellipsoid;
  c.fail("shape", "expected one of cuboid, cylinder, ellipsoid, got '" + s + "'");
}

Eigen::Vector3d vec3(const ConfigNode& c, const std::string& key) {
  const auto v = c.getList<double>(key, 3);
  return {v[0], v[1], v[2]};
}

std::vector<int> intList(const ConfigNode& c, const std::string& key) {
  return c.has(key) ? c.getList<int>(key) : std::vector<int>{};
}
}  // namespace

ClassTable ClassTable::load(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  const ConfigNode list = root.child("classes");
  if (list.size() == 0) list.fail("", "expected a non-empty list of classes");
  ClassTable table;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ConfigNode c = list[i];
    ClassInfo info;
    info.id = c.get<int>("id");
    info.name = c.get<std::string>("name");
    info.shape = parseShape(c);
    info.association_distance = c.get<double>("association_distance");
    info.model_difference = c.get<double>("model_difference");
    if (info.association_distance <= 0) c.fail("association_distance", "must be positive");
    if (info.model_difference <= 0) c.fail("model_difference", "must be positive");
    if (c.has("association_max_slack")) info.association_max_slack = c.get<double>("association_max_slack");
    if (!(info.association_max_slack >= 0)) c.fail("association_max_slack", "must not be negative (0: no cap)");
    info.size_min = vec3(c, "size_min");
    info.size_max = vec3(c, "size_max");
    if ((info.size_min.array() < 0).any() || (info.size_max.array() < info.size_min.array()).any())
      c.fail("size_max", "sizes must satisfy 0 <= size_min <= size_max per axis");
    if (c.has("size_typical")) {
      info.size_typical = vec3(c, "size_typical");
      if ((info.size_typical->array() < info.size_min.array()).any() ||
          (info.size_typical->array() > info.size_max.array()).any())
        c.fail("size_typical", "must lie between size_min and size_max per axis");
    }
    info.semantickitti = intList(c, "semantickitti");
    info.map_labels = intList(c, "map_labels");
    info.family = c.get<std::string>("family", "");
    info.catch_all = c.get<bool>("catch_all", false);
    if (c.has("color")) {
      const auto rgb = c.getList<int>("color", 3);
      info.color = {rgb[0], rgb[1], rgb[2]};
    }
    try {
      table.add(info);
    } catch (const std::invalid_argument& e) {
      c.fail("", e.what());
    }
  }
  root.rejectUnknownKeys();
  return table;
}

Eigen::Vector3d ClassInfo::typicalSize() const {
  if (size_typical) return *size_typical;
  Eigen::Vector3d e;
  for (int i = 0; i < 3; ++i) e[i] = std::sqrt(std::max(size_min[i], 1e-3) * std::max(size_max[i], 1e-3));
  return e.cwiseMin(size_max).cwiseMax(size_min);
}

ClassTable ClassTable::loadDefault() { return load(std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml"); }

void ClassTable::add(const ClassInfo& info) {
  if (classes_.count(info.id)) throw std::invalid_argument("duplicate class id " + std::to_string(info.id));
  if (findByName(info.name)) throw std::invalid_argument("duplicate class name '" + info.name + "'");
  for (const auto& [id, c] : classes_)
    if (!info.family.empty() && c.family == info.family && c.shape != info.shape)
      throw std::invalid_argument("class '" + info.name + "' is in family '" + info.family + "' with class '" + c.name +
                                  "' of another shape");
  classes_[info.id] = info;
}

bool ClassTable::sameKind(int a, int b) const {
  if (a == b) return true;
  const ClassInfo *ca = find(a), *cb = find(b);
  return ca && cb && ((!ca->family.empty() && ca->family == cb->family) || (ca->shape == cb->shape && (ca->catch_all || cb->catch_all)));
}

const ClassInfo* ClassTable::gateClass(int detection_class, int landmark_class) const {
  const ClassInfo *d = find(detection_class), *l = find(landmark_class);
  return d && l && d->catch_all && !l->catch_all ? l : d;
}

const ClassInfo* ClassTable::find(int id) const {
  const auto it = classes_.find(id);
  return it == classes_.end() ? nullptr : &it->second;
}

const ClassInfo& ClassTable::at(int id) const {
  if (const ClassInfo* c = find(id)) return *c;
  throw std::out_of_range("unknown object class id " + std::to_string(id));
}

const ClassInfo* ClassTable::findByName(const std::string& name) const {
  for (const auto& [id, c] : classes_)
    if (c.name == name) return &c;
  return nullptr;
}

std::optional<int> ClassTable::fromSemanticKitti(int label) const {
  for (const auto& [id, c] : classes_)
    for (int l : c.semantickitti)
      if (l == label) return id;
  return std::nullopt;
}

std::optional<int> ClassTable::fromMapLabel(int label) const {
  for (const auto& [id, c] : classes_)
    for (int l : c.map_labels)
      if (l == label) return id;
  return std::nullopt;
}

std::vector<int> ClassTable::ids() const {
  std::vector<int> out;
  for (const auto& kv : classes_) out.push_back(kv.first);
  return out;
}

bool ClassTable::sizePlausible(const Object& o) const {
  const ClassInfo* c = find(o.class_id);
  if (!c) return false;
  const Eigen::Vector3d e = o.extent();
  return (e.array() >= c->size_min.array()).all() && (e.array() <= c->size_max.array()).all();
}

}  // namespace slide
