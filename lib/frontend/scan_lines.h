#pragma once
// The returns of a spinning-LiDAR scan looked up by beam direction: binned by azimuth (0.25
// deg), each bin sorted by elevation. Answers the questions the segmenter asks of the scan's
// geometry: where a set of points ends on each beam through it (its azimuth edges), which
// returns follow a given one on its beam (same elevation, growing or shrinking azimuth),
// whether a nearer return lies just above a point (its upward view is blocked), and where the
// view ends above (the top beam, and the returns standing under it). Points are in the sensor
// frame (sensor at the origin, z up).
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "frontend/instance.h"

namespace slide::frontend {

class ScanLines {
 public:
  // `points`: indices into `cloud` (e.g. the points above ground); both must outlive this.
  ScanLines(const Cloud& cloud, const std::vector<int>& points);

  // The beams through `points` (indices into the cloud): returns within beam_tolerance_deg of
  // each other in elevation form one beam; its edges are its returns of lowest and highest
  // azimuth.
  struct BeamEdges {
    int low, high;  // indices into the cloud
  };
  std::vector<BeamEdges> beamEdges(const std::vector<int>& points, double beam_tolerance_deg) const;

  // Up to `count` of the indexed returns on the beam of cloud point `from` (elevation within
  // beam_tolerance_deg) beyond it in azimuth (direction +1: counter-clockwise, -1: clockwise)
  // by at most window_deg, skipping those marked in `skip` (sized like the cloud); nearest in
  // azimuth first.
  std::vector<int> next(int from, int direction, int count, double window_deg, double beam_tolerance_deg,
                        const std::vector<char>& skip) const;

  // Whether an indexed return nearer than `range` (horizontal metres) lies within 3 deg above
  // the elevation of p, within about 1 deg of its azimuth: something in front hides what
  // stands above p (a crown may be there).
  bool hiddenAbove(const Eigen::Vector3f& p, float range) const;

  // What hides the bottom of `points` (indices into the cloud): for each of their azimuth bins
  // whose lowest return has an indexed return on a line of sight passing at most `below` metres
  // under it (same bin or the next one on each side) nearer by more than `margin` metres, the
  // index of one such return. With a finite `ground_z` (the ground's height under `points`,
  // sensor frame) the lines passing at most `below` metres under the ground there are searched
  // too when the first lines hide nothing: the lowest returns of a face standing on a surface
  // that was taken for the ground (and so left out of the index) end the first lines.
  // `bins` receives the number of azimuth bins of `points`.
  std::vector<int> hiddenBelow(const std::vector<int>& points, float below, float margin, int& bins,
                               float ground_z = std::numeric_limits<float>::quiet_NaN()) const;

  // The share of the azimuth bins of `points` (indices into the cloud) where the face they show
  // goes on past them: the next indexed return above their highest one in the bin (within
  // window_deg of elevation) that is no point of theirs (`in_set`, sized like the cloud), or the
  // next such below their lowest, lies within range_tolerance metres of that return's
  // horizontal range and is not marked `unknown` (sized like the cloud: e.g. returns cut off
  // with the top of the view, whose surface is of unknown extent). A wall far off, whose beams
  // lie farther apart than fine clustering cells, falls into bands that each go on this way; a
  // thing standing free ends at its top (the next beam passes over it to what lies behind) and
  // at its bottom (the ground, not indexed, or its support).
  double continuedFraction(const std::vector<int>& points, const std::vector<char>& in_set,
                           const std::vector<char>& unknown, float range_tolerance, double window_deg) const;

  // The heights (z) of the indexed returns above p in elevation, in its azimuth bin and the
  // next one on each side, nearer than `range` (horizontal metres): what ends the view above p.
  std::vector<float> heightsAbove(const Eigen::Vector3f& p, float range) const;

  // The top beam: its returns lie on z = height + r * tan_elevation (r horizontal). A
  // multi-laser head fires from emitters above the sensor frame's origin: the real
  // SemanticKITTI scans' top beam leaves at +2.0 deg from 0.2-0.24 m above it, so its
  // elevation seen from the origin falls from 3.6 deg at 7 m to 2.2 deg at 50 m.
  struct ViewTop {
    float tan_elevation = 0, height = 0;
    float at(float range) const { return height + range * tan_elevation; }
  };
  // The top of the view where the scan's top beam hits something in most directions. For each
  // origin height within max_height of the sensor's (steps of 0.02 m), the line at the highest
  // elevation of the returns seen from there; of those, the one that the most azimuth bins
  // reach within tolerance_deg (ties: the height nearest the origin). None when it is reached
  // by fewer than min_share of the bins (open sky above most directions: the view cuts
  // nothing off); walls, a ceiling or crowns all around give one.
  std::optional<ViewTop> viewTop(double tolerance_deg, double min_share, double max_height) const;

  // Marks in `mark` (sized like the cloud) the indexed returns that stand under a return at the
  // top of the view (within tolerance_deg of it): in its azimuth bin or a neighbouring one,
  // within range_tolerance metres of its horizontal range. A vertical face returns every beam
  // of an azimuth step at the same range.
  void markUnderTop(const ViewTop& top, double tolerance_deg, float range_tolerance, std::vector<char>& mark) const;

  // Whether an indexed return marked in `mark` (sized like the cloud) lies in the azimuth bin
  // of cloud point p or a neighbouring one, within range_tolerance metres of its horizontal range.
  bool besideMarked(const Eigen::Vector3f& p, const std::vector<char>& mark, float range_tolerance) const;

 private:
  struct Return {
    float azimuth, tan_elevation, range;  // radians; z over horizontal range; horizontal metres
    int index;
  };
  static constexpr int kBins = 1440;
  static int bin(float azimuth);
  static Return polar(const Eigen::Vector3f& p, int index);
  // The cloud points `points` as returns, sorted by azimuth bin, then by elevation.
  std::vector<Return> byBin(const std::vector<int>& points) const;
  // Returns of bin b with tan_elevation in [lo, hi].
  std::pair<const Return*, const Return*> band(int b, float lo, float hi) const;
  const Cloud& cloud_;
  std::vector<int> start_;        // returns_[start_[b] .. start_[b + 1]) lie in bin b
  std::vector<Return> returns_;
};

}  // namespace slide::frontend
