#pragma once
// Per-frame diagnosis of a LiDAR segmenter's instances against the simulator's point labels
// (evaluation only: `slide-bench-frontend --diagnose`). For every scored ground-truth object
// seen in a frame (>= min_points returns within max_range) it says whether an instance of its
// class holds it alone (ok), together with another object or with background returns
// (joined), split over several instances (fragmented), under another class (wrong class), or
// not at all (missed); for every instance whose points come mostly from no object of its class
// it says where they come from (false, by source). Counts are summed over frames and printed
// per class and by the object's returns in the frame, with the first few false instances of
// each kind described (range, extents).
#include <array>
#include <map>
#include <string>
#include <vector>

#include "frontend/instance.h"
#include "io/kitti_scan.h"

namespace slide {

class SegmentDiagnosis {
 public:
  // object_class: ground-truth object id -> class id (moving objects left out); objects seen
  // with at least min_points returns within max_range (horizontal metres) in a frame count.
  SegmentDiagnosis(std::map<int, int> object_class, int min_points, double max_range)
      : object_class_(std::move(object_class)), min_points_(min_points), max_range_(max_range) {}
  void addFrame(const io::LabelledScan& truth, const std::vector<frontend::Instance>& instances);
  void print(const std::string& mode, const std::map<int, std::string>& class_names) const;

 private:
  std::map<int, int> object_class_;
  int min_points_;
  double max_range_;
  // class -> returns bucket (< 60, 60-150, >= 150) -> outcome -> frames
  std::map<int, std::array<std::map<std::string, int>, 3>> objects_;
  // instance class -> source of its points -> instances
  std::map<int, std::map<std::string, int>> false_;
  // ... and the first kSamples of them: frame, range, points, extents (sensor frame)
  static constexpr std::size_t kSamples = 8;
  std::map<int, std::map<std::string, std::vector<std::string>>> false_samples_;
  int frame_ = 0;
};

}  // namespace slide
