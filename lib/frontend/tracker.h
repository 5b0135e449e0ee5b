#pragma once
// Instance tracking across frames in the odometry frame: per-class Hungarian assignment of
// instances to tracks by centroid distance (gated by the class's association distance),
// points accumulated over a sliding window of observations, a minimum age before a track
// yields objects, deletion after missed frames, and rejection of moving objects (tracks whose
// accumulated points grow beyond the class's size limits; a single instance that wide is a
// segmentation error and is dropped).
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "frontend/input_issues.h"
#include "frontend/instance.h"
#include "frontend/shape_fit.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct TrackerParams {
  double gate_scale = 0.5;           // gate = class association_distance * gate_scale
  int min_age = 3;                   // observations before a track yields objects
  int max_missed = 30;               // consecutive missed frames before deletion (a column lost behind another for a while keeps its track)
  int report_max_missed = 1;         // tracks missed longer ago are not reported
  double report_max_range = 0;       // objects farther from the body (m, x-y) are not reported (0: off); they are still tracked, their class votes counted
  std::map<std::string, double> report_max_range_by_class;  // class name -> its own report_max_range (larger objects fit well farther off)
  int max_observations = 10;         // sliding window of observations per track
  int max_points_per_observation = 1500;
  double moving_tolerance = 1.25;    // accumulated extents > class size_max * this: moving
  // A track is moving also when more than this share of an earlier observation's points (and at
  // least moving_vacated_min_points of them) stand where the newest observation's lines of sight
  // passed through (Observation::free_space), with free space at least moving_vacated_depth
  // metres all around them: the object has left that place. A parked car's body blocks every
  // line of sight at its height; grazing lines of sight pass beside its faces. 0: off.
  double moving_vacated_share = 0.0;
  int moving_vacated_min_points = 10;
  double moving_vacated_depth = 0.3;
  // A box track is moving also when its whole extent has shifted: between the newest observation
  // and the latest one at least moving_shift_interval (at most moving_shift_max_interval) seconds
  // older, the centroid and both ends of the points' extent along that shift (their
  // moving_shift_quantile and 1 - that quantile) moved by at least moving_shift metres the same
  // way, the two views alike (point counts and lengths within moving_shift_similarity times, each
  // of at least moving_shift_min_points) and as long along the shift as the class's shortest
  // length allows. Seeing more of a parked car moves one end of its extent, not both; the next car
  // of a row, glimpsed end-on, jumps across its width; a car driving off moves both ends (on a far
  // lane, where few lines of sight cross where it stood). 0: off.
  double moving_shift = 0.0;
  double moving_shift_interval = 0.3;
  double moving_shift_max_interval = 1.0;  // a track seen again after longer is not compared
  // An instance left without a track that shows the whole box of a track seen in the previous
  // frame (and not in this one) shifted so, within this distance (m, x-y), beyond the gate: that
  // car drove on; it continues its track, judged moving (0: off).
  double moving_shift_reach = 0.0;
  // A moving track is looked for where its velocity carries it (for at most
  // moving_shift_max_interval seconds), not where it was last seen: the next view of a passing car
  // continues its track rather than a track another car left there.
  bool moving_predict = false;
  double moving_shift_similarity = 1.5;    // the two views' point counts and lengths within this ratio
  double moving_shift_quantile = 0.1;
  int moving_shift_min_points = 10;  // each of the two observations
  // A box view whose points lie on the last views of two or more static tracks of its class seen
  // in one of the last three frames (the nearest four) is those objects joined by the segmenter (the end faces of two cars
  // parked side by side, clustered together in some frames and apart in others): it is split,
  // each point to the track whose last view lies nearest, when each part holds at least
  // split_min_points and lies at least split_min_gap metres (x-y) from the other, and each track
  // claims (within split_distance) at least split_min_points of it. One car's side, seen whole
  // after stripes of it, has no gap. So also is an earlier view of a track that holds the newest
  // view of a track of its class seen in the same frame: it keeps its own part. 0: off.
  double split_distance = 0.0;
  int split_min_points = 10;
  double split_min_gap = 0.3;
  // Box views of one frame of which each lies on one static track's last view (at least this
  // share of its points within split_distance of it, fewer than split_min_points near any other
  // track's), each within split_min_gap of another, are pieces of one object the segmenter cut:
  // joined into one view before association. 0: off (also when split_distance is 0).
  double join_share = 0.0;
  bool merge_same_shape = true;      // unmatched instances may continue a track of another class of the same shape
  double column_merge_distance = 0.25;  // column tracks this close (m, x-y) are one object: merged (0: off)
  // A track of a catch-all class (ClassInfo::catch_all) and one of a named class of its shape
  // whose last centroids are this close (m) follow one object the detector named in some frames
  // and missed in others: merged, the class the votes give (0: off).
  double catch_all_merge_distance = 0.0;
  // An instance whose own footprint exceeds its class's size (x moving_tolerance) is several
  // objects joined by the segmenter: dropped (counted), so it cannot make a track look moving.
  bool drop_oversized = true;
  // Cuboid tracks whose points together fit in one footprint this wide (and no longer than the
  // class's size_max) are one object: merged (0: off). Below the gap of two cars side by side
  // (1.8 m wide at 2.6 m pitch) plus a stripe of the next one.
  double box_merge_width = 2.2;
  // ... and whose joint footprint is at most this much longer than the longer of the two: one
  // holds the other (two cars' end faces side by side, seen from an aisle, are not merged).
  double box_merge_growth = 0.5;
  // A track's length there is what one view of it shows: this quantile of its observations'
  // extents along the joint footprint's length (1: the longest single view), not all its points
  // together, so that one view joining two neighbours (the noses of two cars parked side by
  // side taken in as one cluster) does not make a track hold its neighbour.
  double box_merge_view_quantile = 0.8;
  // A box none of whose faces was seen as long as its class's shortest length may have its length
  // along either axis (a car's lone end face, or a stretch of its side seen through a gap): it
  // takes the reading whose heading the boxes of its class within this radius (m, x-y) whose
  // length was seen agree with more (modulo 180 deg). Parked cars stand parallel to their
  // neighbours. 0: off (the fit's own guess).
  double parallel_radius = 10.0;
  // ... or within this radius when no box seen whole stands within parallel_radius (a row of
  // cars seen end-on from an aisle, none seen lengthwise).
  double parallel_fallback_radius = 10.0;
  // Two reported boxes of one class whose footprints overlap by more than this share of the
  // smaller one's are one object tracked in two pieces: reported as one box fitted to both
  // tracks' points (0: off).
  double box_overlap = 0.5;
  // ... also when their centres lie within this (m, x-y) and a pair of their readings (each box's
  // other reading too) overlaps so: one car tracked twice, read one way by one track and the other
  // way by the other (0: off). Boxes are joined again once their readings are settled
  // (parallel_radius).
  double box_same_centre = 0.5;
  // An ellipsoid track's report leaves out views wider than this times its median view
  // (Track::accumulated; 0: off).
  double ellipsoid_view_growth = 0.0;
  // A reported box of which the other reported boxes of its class cover more than this share
  // of the footprint stands across its neighbours (the end faces of two cars parked side by
  // side, read as one car's side): not reported (0: off).
  double box_across = 0.2;
  // Two reported ellipsoids of one kind (ClassTable::sameKind) whose centres lie this close (m)
  // are one object on two tracks (objects stand at least their radii apart): the one of fewer
  // observations is not reported (0: off).
  double ellipsoid_same_place = 0.0;
};

// One instance added to a track, in the odometry frame.
struct Observation {
  Cloud points;
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();  // the body position it was seen from
  std::int64_t utime = 0;                               // the frame's time
  Cloud free_space;  // cells near it the sensor saw through (Instance::free_space)
};

struct Track {
  std::int64_t id = 0;
  int class_id = 0;
  int hits = 0;
  int missed = 0;
  bool moving = false;
  double confidence_sum = 0;
  std::map<int, double> class_votes;  // observations per class weighed by confidence; class_id is the largest
  Eigen::Vector3d last_centroid = Eigen::Vector3d::Zero();  // odometry frame
  std::int64_t last_utime = 0;                              // when last_centroid was seen
  // A moving track's velocity (odometry frame, m/s, x-y) from its last two views: where it is
  // looked for in the next frame (TrackerParams::moving_predict).
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  std::deque<Observation> observations;  // the latest max_observations
  // The observations' points together; with max_growth > 0 (ellipsoid classes) leaving out the
  // views wider (x-y extent) than max_growth times the median view of at least three: a frame
  // in which a neighbour took the track's label (a monitor on a table named "table") joined it.
  // Views that grow as the robot nears are left out too while the narrower ones are the most
  // (leaving out only a minority of wide views, at most a fifth, lost the indoor gain).
  Cloud accumulated(double max_growth = 0.0) const;
  Cloud freeSpace() const;  // the observations' free_space cells together
  // Where the accumulated points were seen from: the mean of the observations' viewpoints,
  // weighted by their points (a partly seen object is completed away from it).
  Eigen::Vector3d viewpoint() const;
};

class Tracker {
 public:
  Tracker(ClassTable classes, TrackerParams params, FitParams fit);

  // One frame: instances (sensor/body frame) at odometry pose frame.odom_pose.
  void update(const FrameInstances& frame, InputIssues& issues);
  // Fitted models of the confirmed, static, recently seen tracks in the body frame of
  // T_odom_body; object ids are track ids. Recently: missed in at most
  // max(report_max_missed, frames_since_report - 1) frames, where frames_since_report counts
  // the frames since the previous report (a key pose) including this one: a track confirmed
  // between two key poses and lost just before the second is still reported once. A box whose
  // length was not seen carries the reading not taken (parallel_radius) as Object::other_reading.
  std::vector<Object> objectsInBody(const Pose& T_odom_body, int frames_since_report = 0) const;

  const std::map<std::int64_t, Track>& tracks() const { return tracks_; }
  const ClassTable& classes() const { return classes_; }

 private:
  // report_max_range of a class (report_max_range_by_class or the common one; 0: no limit).
  double reportRange(int class_id) const;
  bool exceedsClassSize(const Track& t) const;
  bool exceedsClassSize(const std::vector<cv::Point2f>& xy, int class_id) const;
  // Whether the track's object has left where it was: the points of its other observations lie
  // where `newest`'s lines of sight passed through (TrackerParams::moving_vacated_share).
  // `newest` may be one of t's observations (then it is not tested against itself).
  bool vacated(const Track& t, const Observation& newest) const;
  // Whether `newest` shows a box track's whole extent shifted (TrackerParams::moving_shift) against
  // the track's latest observation at least min_interval seconds older than it.
  bool shifted(const Track& t, const Observation& newest, double min_interval) const;
  // Every two tracks that `one_object` says follow one object are merged into the older: two
  // column tracks within column_merge_distance (a trunk's instances alternated between them, or
  // it was split in a frame), a catch-all and a named track within catch_all_merge_distance. A
  // merged track counts as matched in this frame when either half was (`matched`).
  void mergeTracks(std::map<std::int64_t, bool>& matched, const std::function<bool(const Track&, const Track&)>& one_object);
  // An earlier view of a box track matched in this frame that also holds the newest view of
  // another one matched in this frame (the two joined by the segmenter in a frame before the other
  // had a track) keeps only its own part (TrackerParams::split_distance).
  void splitEarlierViews(const std::map<std::int64_t, bool>& matched);
  // Two static tracks of one cuboid class whose points together fit in one footprint no
  // longer than the class's size_max, no wider than box_merge_width and no more than
  // box_merge_growth longer than the longer track's own follow one object
  // (a car's side seen at a grazing angle comes in stripes that start tracks of their own):
  // merged into the older.
  void mergeBoxTracks(std::map<std::int64_t, bool>& matched);
  // The model of `points` (odometry frame) seen from `view`, in the body frame of T_body_odom,
  // carrying the track's id, hits and mean confidence; its other reading into *other if asked.
  // free_space: cells seen empty near it (odometry frame).
  std::optional<Object> fitPoints(const Cloud& points, const Cloud& free_space, const Eigen::Vector3d& view,
                                  int class_id, std::int64_t id, int hits, double confidence_sum,
                                  const Pose& T_body_odom, std::optional<Object>* other) const;
  // Reported boxes of one class whose footprints overlap by more than box_overlap of the smaller
  // one's: the older's entry becomes the fit of all their tracks' points, the younger's is dropped.
  void joinOverlappingBoxes(std::vector<std::pair<Object, std::optional<Object>>>& fits, const Pose& T_body_odom,
                            bool readings) const;
  // Drops the boxes that stand across their neighbours (box_across), the most covered first.
  void dropBoxesAcrossNeighbours(std::vector<std::pair<Object, std::optional<Object>>>& fits) const;
  // Of two ellipsoids of one kind at one place (ellipsoid_same_place), drops the one of fewer observations.
  void dropEllipsoidsAtOnePlace(std::vector<std::pair<Object, std::optional<Object>>>& fits) const;

  ClassTable classes_;
  std::map<int, double> report_range_of_class_;  // report_max_range_by_class by class id
  TrackerParams params_;
  FitParams fit_;
  std::map<std::int64_t, Track> tracks_;
  std::int64_t next_id_ = 0;
};

}  // namespace slide::frontend
