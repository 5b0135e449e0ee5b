#pragma once
// Segmentation of scans that carry per-point classes only (a range-image network such as
// RangeNet++, the detection emulator, or the simulator's labels in an oracle run): grid
// clustering of each class's points. Instance ids, when a scan has them, are ignored: a
// detector gives none. Points of classes outside the ClassTable (road, building,
// vegetation...) are not objects and are dropped.
//
// Robust to a real network's errors: each object-labelled point first takes the label most
// points around it in 3-D carry (label_vote.h: labels bled across the range image's
// boundaries rejoin their surface); with merge_cylinders, trunk and pole points (the classes
// a network confuses most) are clustered together and each cluster takes the class most of
// its points carry, so a half-confused pole stays one object; cylinder classes are clustered
// on x, y only, so a column split in height by occlusion or bled labels stays one; boundary points bled into the
// background and shadows behind objects form small separate clusters that min_points drops,
// and flat patches (ground labelled as an object) fall below the class's height; car points
// just above the labelled ground beside them (its bled edge) are left out.
#include <map>
#include <string>
#include <vector>

#include "frontend/grid_clustering.h"
#include "frontend/label_vote.h"
#include "frontend/free_space.h"
#include "frontend/view_notch.h"
#include "frontend/segmenter.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct LabelledSegmenterParams {
  GridClusterParams cluster{0.3, false, 15};
  int min_points = 15;          // instances with fewer points are dropped
  double max_range = 80.0;      // metres, horizontal
  bool merge_cylinders = true;  // cluster all cylinder classes together, majority class per cluster
  double min_height_fraction = 0.5;  // clusters lower than this times their class's size_min z are dropped
  // Each object-labelled point first takes the label most points in the 3 x 3 x 3 cells of this
  // side around it carry (label_vote.h: labels bled across range-image boundaries; 0: off).
  double vote_cell = 0.07;  // metres
  // Cluster cell per class name, for classes whose objects stand closer together than
  // cluster.cell joins (chairs at a table, monitors side by side, trunks); others use
  // cluster.cell. With merge_cylinders the cylinder classes, clustered together, take the finest
  // of their cells.
  std::map<std::string, double> cluster_cell_by_class;
  // A cluster of a cuboid class whose footprint exceeds the class's size_max is clustered
  // again on cells half as large, down to this cell (cars parked a few decimetres apart join
  // at cluster.cell); cluster.cell or more: off.
  double min_split_cell = 0.15;
  // A cuboid-class cluster within the class's size that falls apart on these cells into two or
  // more parts of at least min_points is split into them (cell 0: off; geometric car.gap_cell).
  // Clustered on x, y whatever `planar` says: the gap between two cars is a vertical slot.
  GridClusterParams gap_cluster{0.15, true, 40};
  // Points of a cuboid class at most this high above the lowest point labelled ground within
  // about ground_cell of them are left out: ground bled into a car's labels stretches its
  // footprint towards the sensor (0: off). Where nothing near is labelled ground (a car's far
  // half seen over another) nothing is left out.
  double cuboid_ground_strip = 0.1;  // metres
  double ground_cell = 0.5;          // metres
  std::vector<int> ground_labels{40, 44, 48, 49, 60, 72};  // the labeller's ground (SemanticKITTI ids: road, parking, ...)
  NotchSplitParams notch{0.4, 0.0};  // depth 0: off (config/frontend.yaml says why); on, a cuboid-class cluster with a notch in its view is split there (view_notch.h)
  // Each cuboid-class instance carries the cells near it that the scan saw through in a car
  // body's height band (Instance::free_space; cell 0: none), its ground the lowest labelled
  // ground near its points.
  FreeSpaceParams free_space{0.0};
  // Two clusters of one ellipsoid class that together fit the class's size_max are one object
  // seen in two pieces: one above the other (at least stacked_overlap of the smaller's points lie
  // in the other's x-y box: a chair's seat and back), or cut in two by something in front (a table
  // behind a chair) when they stand at most max_gap metres apart (x-y) and the returns between
  // them in azimuth, at their height, lie at least min_nearer metres nearer than both
  // (min_returns of them, min_share nearer). max_gap 0: off (both); stacked_overlap 0: off.
  struct EllipsoidJoin {
    double max_gap = 0.0;
    double min_nearer = 0.3;
    int min_returns = 5;
    double min_share = 0.8;
    double stacked_overlap = 0.0;
  } ellipsoid_join;
  // Class-vote weight of a catch-all instance (the geometric segmenter's other_confidence): a
  // detector that misses a chair far off calls it "other" for many frames before it names it
  // near; named votes outweigh that many catch-all ones (tracker; the optimizer's landmarks).
  double other_confidence = 1.0;
  // A cluster of a catch-all class (ClassInfo::catch_all) of which more than max_share of the
  // points have a point of a named class within about `radius` metres (the same or a
  // neighbouring cell of that side) is the leftover of named objects' labels, not an object:
  // dropped. A labeller's per-point noise and boundary errors scatter catch-all labels over
  // furniture; the vote thins them, and what is left, clustered, spans a table and its
  // monitors. A bin by a wall has wall around it. radius 0: off.
  struct CatchAllDebris {
    double radius = 0.0;
    double max_share = 0.5;
  } catch_all_debris;
};

class LabelledSegmenter : public LidarSegmenter {
 public:
  // Throws std::invalid_argument for a cluster_cell_by_class name that is not in `classes`.
  LabelledSegmenter(ClassTable classes, LabelledSegmenterParams params);
  std::string name() const override { return "labelled"; }
  // Scans without labels give no instances and count "scan without labels".
  std::vector<Instance> segment(const io::LabelledScan& scan, InputIssues& issues) const override;

 private:
  ClassTable classes_;
  LabelledSegmenterParams params_;
  std::map<int, double> cell_of_class_;  // cluster_cell_by_class by class id
  double cylinder_cell_ = 0;             // the finest cell of a cylinder class (0: none given)
};

}  // namespace slide::frontend
