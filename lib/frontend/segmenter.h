#pragma once
// The segmenter interface: one scan in, object instances (class, points in the sensor frame)
// out. The labelled and geometric segmenters implement it; a learned model plugs in either as
// a PointLabeler (per-point classes, e.g. RangeNet++) whose output feeds the labelled
// segmenter, or as a whole LidarSegmenter of its own.
#include <memory>
#include <string>
#include <vector>

#include "frontend/input_issues.h"
#include "frontend/instance.h"
#include "io/kitti_scan.h"

namespace slide::frontend {

class LidarSegmenter {
 public:
  virtual ~LidarSegmenter() = default;
  virtual std::string name() const = 0;
  // Instances of one scan; bad points (non-finite) are skipped and counted in `issues`.
  virtual std::vector<Instance> segment(const io::LabelledScan& scan, InputIssues& issues) const = 0;
};

// A learned per-point classifier: fills scan.semantic (SemanticKITTI class ids) and, when it
// separates instances, scan.instance (0 elsewhere).
class PointLabeler {
 public:
  virtual ~PointLabeler() = default;
  virtual std::string name() const = 0;
  virtual void label(io::LabelledScan& scan) const = 0;
};

// Runs a PointLabeler, then segments its labels with `labelled` (e.g. a LabelledSegmenter).
class LearnedLidarSegmenter : public LidarSegmenter {
 public:
  LearnedLidarSegmenter(std::shared_ptr<const PointLabeler> labeler, std::shared_ptr<const LidarSegmenter> labelled)
      : labeler_(std::move(labeler)), labelled_(std::move(labelled)) {}
  std::string name() const override { return labeler_->name() + "+" + labelled_->name(); }
  std::vector<Instance> segment(const io::LabelledScan& scan, InputIssues& issues) const override {
    io::LabelledScan copy = scan;
    labeler_->label(copy);
    if (copy.semantic.size() != copy.size() || (!copy.instance.empty() && copy.instance.size() != copy.size())) {
      issues.count("labeler output size mismatch");
      return {};
    }
    if (copy.instance.empty()) copy.instance.assign(copy.size(), 0);
    return labelled_->segment(copy, issues);
  }

 private:
  std::shared_ptr<const PointLabeler> labeler_;
  std::shared_ptr<const LidarSegmenter> labelled_;
};

}  // namespace slide::frontend
