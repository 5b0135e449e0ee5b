#pragma once
// Front-end checks on real data: the TLS trunk slice and pine plot, and the two
// SemanticKITTI scans in labelled and geometric mode.
#include <string>
#include <vector>

#include "frontend/frontend_config.h"
#include "eval/label_iou.h"
#include "eval/labelled_scan_score.h"
#include "frontend/segmenter.h"
#include "objects/class_table.h"

namespace slide {

struct TlsResult {
  double fitted_radius = 0;
  double algebraic_radius = 0;  // algebraic LS circle of all slice points (trunk + branch)
  double trunk_radius = 0;      // eval::referenceCircle: least median of squares, then LS on its inliers
  int trunk_points = 0;         // the points that refit used
  int pine_trunks = 0;               // cylinders found in pine_plot.xyz
  std::vector<double> pine_radii;
  std::vector<Eigen::Vector2d> pine_positions;
};
TlsResult evaluateTls(const std::string& data_dir, const ClassTable& classes, const frontend::FrontendConfig& cfg);

// One labelled ground-truth object of a SemanticKITTI scan and whether the mode found it.
struct KittiTarget {
  int class_id = 0;        // car, trunk or pole (our ids)
  int instance = 0;        // SemanticKITTI instance id (0 for trunks/poles: a cluster)
  int points = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  bool found = false;
  std::string fitted;      // what matched (e.g. "cuboid 4.3x1.8x1.5")
};

struct KittiScanResult {
  std::string scan, mode;
  std::vector<KittiTarget> targets;
  int cuboids = 0, cylinders = 0, ellipsoids = 0;   // fitted objects of the mode
  eval::ScanScore score;                                  // targets, duplicates, false objects
  std::vector<std::string> unmatched;               // one line per unmatched cuboid / cylinder
  std::vector<double> segment_fit_ms;               // thread CPU time, one per run
  std::vector<double> segment_fit_wall_ms;          // wall-clock time, one per run
};

// Runs `segmenter` + fitting `runs` times on the scan (timing each) and matches the fitted
// objects of the last run against the scan's labels.
KittiScanResult evaluateKittiScan(const std::string& bin_path, const frontend::LidarSegmenter& segmenter,
                                  const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs);

// Runs `labeler` `runs` times on the scan, timing each (thread CPU: projection, inference,
// back-projection), and adds its last labels, scored with the scan's SemanticKITTI labels, to
// `iou`. Returns the times in ms.
std::vector<double> evaluateLearnedLabels(const std::string& bin_path, const frontend::PointLabeler& labeler, int runs,
                                          eval::LabelIou& iou);

}  // namespace slide
