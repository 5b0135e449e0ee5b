#pragma once
// Segmentation of scans that carry per-point classes (SemanticKITTI labels from a dataset,
// the simulator or a learned model): one instance per (class, instance id) where instance ids
// are given, grid clustering of each class's remaining points otherwise. Points of classes
// outside the ClassTable (road, building, vegetation...) are not objects and are dropped.
#include "frontend/grid_clustering.h"
#include "frontend/segmenter.h"
#include "objects/class_table.h"

namespace slide {

struct LabelledSegmenterParams {
  GridClusterParams cluster{0.3, false, 15};
  int min_points = 15;      // instances with fewer points are dropped
  double max_range = 80.0;  // metres, horizontal
};

class LabelledSegmenter : public LidarSegmenter {
 public:
  LabelledSegmenter(ClassTable classes, LabelledSegmenterParams params)
      : classes_(std::move(classes)), params_(params) {}
  std::string name() const override { return "labelled"; }
  // Scans without labels give no instances and count "scan without labels".
  std::vector<Instance> segment(const LabelledScan& scan, InputIssues& issues) const override;

 private:
  ClassTable classes_;
  LabelledSegmenterParams params_;
};

}  // namespace slide
