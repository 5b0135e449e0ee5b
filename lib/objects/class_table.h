#pragma once
// The one table of object classes (config/classes.yaml) shared by every stage: shape model,
// association thresholds, plausible sizes and the external labels that mean each class.
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "objects/object.h"

namespace slide {

struct ClassInfo {
  int id = 0;
  std::string name;
  Shape shape = Shape::Ellipsoid;
  double association_distance = 1.0;  // metres between centres (cylinders: to the axis)
  double model_difference = 1.0;      // metres, see modelDifference()
  // Metres a detection's own position uncertainty may widen association_distance by (0: no cap).
  // Cars park 2.5 m apart: a car 40 m off (bearing sigma 2 m) would be associable 7 m away.
  double association_max_slack = 0.0;
  Eigen::Vector3d size_min = Eigen::Vector3d::Zero();  // bounding-box extents, see Object::extent()
  Eigen::Vector3d size_max = Eigen::Vector3d::Constant(1e9);
  // Typical extents (completion of partly seen objects); default per axis sqrt(size_min * size_max).
  std::optional<Eigen::Vector3d> size_typical;
  Eigen::Vector3d typicalSize() const;
  std::vector<int> semantickitti;     // SemanticKITTI class ids of this class
  std::vector<int> map_labels;        // labels meaning this class in object-map text files
  Eigen::Vector3i color{128, 128, 128};  // RGB for plots
  // Classes of one family (same shape) name the same kind of object seen in different ways
  // (a thin trunk whose crown is out of view looks like a pole): one object may be observed
  // under any of them, and a landmark takes the class most of its observations gave.
  std::string family;
  // A catch-all: the detector's label for things it has no class for ("other"). Its
  // observations may be of any object of its shape (a chair the detector missed), so a
  // catch-all track or landmark and a named one of that shape on one object are one.
  bool catch_all = false;
};

class ClassTable {
 public:
  // Loads config/classes.yaml-style files; throws ConfigError naming file, key and problem.
  static ClassTable load(const std::string& path);
  // The table shipped in config/classes.yaml of the source tree.
  static ClassTable loadDefault();

  void add(const ClassInfo& info);  // throws std::invalid_argument on a duplicate id or name
  const ClassInfo* find(int id) const;
  const ClassInfo& at(int id) const;  // throws std::out_of_range naming the unknown id
  // The same class, two classes of one family, or a catch-all and a class of its shape:
  // detections of either may be one object.
  bool sameKind(int a, int b) const;
  // The class whose association thresholds apply to a detection of one class against a landmark
  // of another: the landmark's when the detection's is a catch-all and the landmark's is not (the
  // object is what that class names), else the detection's. Null when the detection's is unknown.
  const ClassInfo* gateClass(int detection_class, int landmark_class) const;
  const ClassInfo* findByName(const std::string& name) const;
  std::optional<int> fromSemanticKitti(int semantic_label) const;
  std::optional<int> fromMapLabel(int label) const;
  std::vector<int> ids() const;
  bool sizePlausible(const Object& o) const;  // extents inside the class's size range

 private:
  std::map<int, ClassInfo> classes_;
};

}  // namespace slide
