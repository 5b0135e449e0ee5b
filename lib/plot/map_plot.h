#pragma once
// The picture of a run: object maps (filled by class colour, outlined by robot colour) and
// trajectories (one colour per robot), ground truth overlaid as black dashed outlines and
// lines, in a top view with metre axes or an oblique view with a ground grid and scale bar,
// and a legend of classes and robots.
#include <string>
#include <vector>

#include "objects/class_table.h"
#include "objects/object.h"
#include "plot/canvas.h"
#include "plot/view.h"

namespace slide::plot {

struct PlotMap {
  std::string name;  // shown in the legend, e.g. "robot0 map"
  std::vector<Object> objects;
  int robot = 0;     // picks the outline colour
  bool ground_truth = false;
};

struct PlotTrajectory {
  std::string name;
  std::vector<Eigen::Vector3d> positions;
  int robot = 0;
  bool ground_truth = false;
  // Optional, one per position (e.g. ATE): colours the line by value with a colour bar.
  std::vector<double> values;
};

// The outcome of scoring a map against ground truth, drawn over the map (see
// eval/object_matching.h): matched pairs joined by a line, false positives crossed out,
// missed ground-truth objects ringed.
struct MatchOverlay {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> matches;  // (estimate, truth) positions
  std::vector<Eigen::Vector3d> false_positives, missed;
};

struct MapPlotOptions {
  View view = View::top();
  int width = 1400, height = 1000;
  std::string title = "object map", subtitle;
  double fill_opacity = 0.6;
  bool label_ids = false;  // write object ids next to objects
  std::string values_label = "error [m]";  // colour bar label for PlotTrajectory::values
  MatchOverlay overlay;
  // A point cloud under the objects (e.g. the scan they came from): dots shaded by height,
  // at most one per pixel.
  std::vector<Eigen::Vector3d> points;
};

Canvas plotMap(const std::vector<PlotMap>& maps, const std::vector<PlotTrajectory>& trajectories,
               const ClassTable& classes, const MapPlotOptions& opts);

}  // namespace slide::plot
