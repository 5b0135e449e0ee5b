#include "frontend/tracker.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <unordered_set>
#include <opencv2/imgproc.hpp>

#include "assignment/hungarian.h"
#include "objects/association.h"

namespace slide::frontend {

namespace {
Cloud subsample(const Cloud& c, int max_points) {
  if (static_cast<int>(c.size()) <= max_points || max_points <= 0) return c;
  Cloud out;
  out.reserve(max_points);
  const double step = static_cast<double>(c.size()) / max_points;
  for (int k = 0; k < max_points; ++k) out.push_back(c[static_cast<std::size_t>(k * step)]);
  return out;
}

// Seconds from utime a to utime b, in floating point: times off a bus may be anything, and their
// integer difference may overflow.
double secondsBetween(std::int64_t a, std::int64_t b) { return 1e-6 * (static_cast<double>(b) - static_cast<double>(a)); }

// Free cells kept per observation, per point kept: a car's cells within its typical length number a
// few thousand at most; a hostile instance may carry any number.
constexpr int kFreeCellsPerPoint = 4;
// Points of a track's last view a box view is split by (TrackerParams::split_distance).
constexpr int kSplitPointsPerTrack = 300;
// ... and how many frames before this one a track may have been missed (its view there split),
// and how many tracks (the nearest) a view is split between: a hostile frame may leave any number
// of tracks in one place.
constexpr int kSplitMaxMissed = 2;
constexpr std::size_t kSplitMaxTracks = 4;
// The largest pieces of one frame's views on one track that are joined (TrackerParams::join_share).
constexpr std::size_t kJoinMaxPieces = 8;

// The x-y bounding box of c, grown by `reach` on every side.
Eigen::AlignedBox2f grownBox(const Cloud& c, float reach) {
  Eigen::AlignedBox2f box;
  for (const auto& p : c) box.extend(p.head<2>());
  box.min().array() -= reach;
  box.max().array() += reach;
  return box;
}

// Nearest x-y distance from p to the points of c (infinity for none).
float nearestXy(const Eigen::Vector3f& p, const Cloud& c) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& q : c) best = std::min(best, (q.head<2>() - p.head<2>()).squaredNorm());
  return std::sqrt(best);
}

// The parts of `view` on the tracks' last views `lasts` (TrackerParams::split_distance): each point
// to the nearest last view; empty when the view is not split.
std::vector<Cloud> partsOnTracks(const Cloud& view, const std::vector<const Cloud*>& lasts, double claim, int min_points,
                                 double min_gap) {
  if (lasts.size() < 2) return {};
  std::vector<Cloud> parts(lasts.size());
  std::vector<int> claimed(lasts.size(), 0);
  for (const auto& p : view) {
    std::size_t best = 0;
    float best_d = std::numeric_limits<float>::infinity();
    for (std::size_t j = 0; j < lasts.size(); ++j)
      if (const float d = nearestXy(p, *lasts[j]); d < best_d) best_d = d, best = j;
    parts[best].push_back(p);
    claimed[best] += best_d <= claim;
  }
  std::vector<Cloud> out;
  for (std::size_t j = 0; j < parts.size(); ++j)
    if (static_cast<int>(parts[j].size()) >= min_points && claimed[j] >= min_points) out.push_back(std::move(parts[j]));
  if (out.size() < 2) return {};
  // Apart: every pair of parts at least min_gap from each other.
  for (std::size_t a = 0; a < out.size(); ++a)
    for (std::size_t b = a + 1; b < out.size(); ++b)
      for (const auto& p : out[a])
        if (nearestXy(p, out[b]) < min_gap) return {};
  return out;
}

// The one of `lasts` (tracks' last views) that `piece` lies on: it claims (within `claim`) at
// least `share` of the piece's points and every other fewer than `min_points`; -1 for none.
int soleTrack(const Cloud& piece, const std::vector<const Cloud*>& lasts, double claim, double share, int min_points) {
  int owner = -1;
  for (std::size_t j = 0; j < lasts.size(); ++j) {
    int n = 0;
    for (const auto& p : piece) n += nearestXy(p, *lasts[j]) <= claim;
    if (n >= share * static_cast<double>(piece.size())) {
      if (owner >= 0) return -1;
      owner = static_cast<int>(j);
    } else if (n >= min_points) {
      return -1;
    }
  }
  return owner;
}

// Groups of `pieces` (one frame's views of a class, each with the track it alone lies on or -1)
// that are one object cut by the segmenter (TrackerParams::join_share): pieces on one track, the
// largest first and then each within `min_gap` of those already in the group (farther apart they
// are two objects, as the split step says: a track's view may have held two noses). Only groups
// of two or more.
std::vector<std::vector<std::size_t>> piecesOfOneView(const std::vector<Cloud>& pieces, const std::vector<std::int64_t>& owner,
                                                      double min_gap) {
  std::map<std::int64_t, std::vector<std::size_t>> on_track;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (owner[i] >= 0) on_track[owner[i]].push_back(i);
  std::vector<std::vector<std::size_t>> groups;
  for (auto& [id, on] : on_track) {
    if (on.size() < 2) continue;
    std::sort(on.begin(), on.end(), [&](std::size_t a, std::size_t b) { return pieces[a].size() > pieces[b].size(); });
    if (on.size() > kJoinMaxPieces) on.resize(kJoinMaxPieces);
    std::vector<std::size_t> group = {on.front()};
    Cloud near = pieces[on.front()];
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t i : on) {
        if (std::find(group.begin(), group.end(), i) != group.end()) continue;
        float gap = std::numeric_limits<float>::infinity();
        for (const auto& q : pieces[i])
          if ((gap = std::min(gap, nearestXy(q, near))) < min_gap) break;
        if (gap >= min_gap) continue;
        group.push_back(i);
        near.insert(near.end(), pieces[i].begin(), pieces[i].end());
        grew = true;
      }
    }
    if (group.size() >= 2) groups.push_back(std::move(group));
  }
  return groups;
}

// Moves `younger`'s observations, votes and counts into `older` (the lower id). The merged
// track is where the more recently seen of the two was; seen in the same frame, where the one
// of the class the votes give was (a chair's view, not the back the detector called "other").
void absorb(Track& older, Track& younger, int max_observations) {
  const int older_class = older.class_id;
  older.hits += younger.hits;
  older.confidence_sum += younger.confidence_sum;
  for (const auto& [c, v] : younger.class_votes) older.class_votes[c] += v;
  older.class_id = std::max_element(older.class_votes.begin(), older.class_votes.end(),
                                    [](const auto& x, const auto& y) { return x.second < y.second; })->first;
  if (younger.missed < older.missed ||
      (younger.missed == older.missed && older_class != older.class_id && younger.class_id == older.class_id))
    older.missed = younger.missed, older.last_centroid = younger.last_centroid, older.last_utime = younger.last_utime,
    older.velocity = younger.velocity;
  for (auto& o : younger.observations) older.observations.push_back(std::move(o));
  while (static_cast<int>(older.observations.size()) > max_observations) older.observations.pop_front();
  older.moving = older.moving || younger.moving;
}

// What one view of a track shows along `axis` (x-y, unit): the `quantile` of its observations'
// extents along it.
double viewLength(const Track& t, const cv::Point2f& axis, double quantile) {
  std::vector<double> lengths;
  for (const auto& o : t.observations) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const auto& p : o.points) {
      const float d = p.x() * axis.x + p.y() * axis.y;
      lo = std::min(lo, d), hi = std::max(hi, d);
    }
    if (hi > lo) lengths.push_back(hi - lo);
  }
  if (lengths.empty()) return 0.0;
  const auto k = std::min(lengths.size() - 1, static_cast<std::size_t>(quantile * static_cast<double>(lengths.size())));
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(k), lengths.end());
  return lengths[k];
}

// Up to `max_points` of the track's accumulated points on the ground plane, evenly spread.
void footprintSample(const Track& t, std::size_t max_points, std::vector<cv::Point2f>& out) {
  std::size_t n = 0;
  for (const auto& o : t.observations) n += o.points.size();
  const std::size_t step = std::max<std::size_t>(1, n / std::max<std::size_t>(1, max_points));
  std::size_t k = 0;
  for (const auto& o : t.observations)
    for (const auto& p : o.points)
      if (k++ % step == 0) out.emplace_back(p.x(), p.y());
}

// The cells a scan saw through near an object (Observation::free_space) on the ground plane, in
// pixels of `pixel` metres: each cell covers the pixels within about half a pixel of its centre
// and the 8 around. A point lies deep in free space when every pixel within `depth` of its own
// is covered: lines of sight passed all around it, not just along a face beside it.
class FreeRaster {
 public:
  // Only the cells within `region` (where the points to test lie; at most kMaxSide metres on a
  // side, else nothing is covered) are rasterised: a hostile instance may carry cells anywhere.
  FreeRaster(const Cloud& free, double pixel, double depth, const Eigen::AlignedBox2d& region)
      : inv_(1.0 / pixel), reach_(static_cast<int>(std::ceil(depth / pixel - 1e-9))) {
    if (free.empty() || region.isEmpty() || (region.sizes().array() > kMaxSide).any()) return;
    // On the 0.1 m grid through the odometry origin: the same cells cover the same pixels
    // whichever points the track holds.
    origin_ = ((region.min() - Eigen::Vector2d::Constant(depth + 2 * pixel)) * inv_).array().floor().matrix() * pixel;
    nx_ = static_cast<int>((region.sizes().x() + 2 * depth) * inv_) + 6;
    ny_ = static_cast<int>((region.sizes().y() + 2 * depth) * inv_) + 6;
    std::vector<char> covered(static_cast<std::size_t>(nx_) * ny_, 0);
    for (const auto& q : free) {
      if (!q.allFinite() || q.x() < origin_.x() - pixel || q.y() < origin_.y() - pixel ||
          q.x() > origin_.x() + (nx_ + 1) * pixel || q.y() > origin_.y() + (ny_ + 1) * pixel)
        continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = pixelOf(q.x(), origin_.x()) + dx, v = pixelOf(q.y(), origin_.y()) + dy;
          if (u >= 0 && v >= 0 && u < nx_ && v < ny_) covered[static_cast<std::size_t>(v) * nx_ + u] = 1;
        }
    }
    // Summed-area table: covered pixels in any block in constant time.
    sum_.assign(static_cast<std::size_t>(nx_ + 1) * (ny_ + 1), 0);
    for (int v = 0; v < ny_; ++v)
      for (int u = 0; u < nx_; ++u)
        sum_[(v + 1) * (nx_ + 1) + u + 1] = covered[static_cast<std::size_t>(v) * nx_ + u] + sum_[v * (nx_ + 1) + u + 1] +
                                            sum_[(v + 1) * (nx_ + 1) + u] - sum_[v * (nx_ + 1) + u];
  }
  // How many of up to `max_points` of `pts` (evenly spread) lie deep in free space, and of how many.
  std::pair<int, int> count(const Cloud& pts, std::size_t max_points) const {
    if (sum_.empty() || pts.empty()) return {0, 0};
    const std::size_t step = std::max<std::size_t>(1, pts.size() / max_points);
    const int side = 2 * reach_ + 1;
    int in = 0, n = 0;
    for (std::size_t k = 0; k < pts.size(); k += step, ++n) {
      if (!pts[k].allFinite()) continue;
      const double fu = std::floor((pts[k].x() - origin_.x()) * inv_), fv = std::floor((pts[k].y() - origin_.y()) * inv_);
      if (!(fu >= 0 && fv >= 0 && fu < nx_ && fv < ny_)) continue;
      const int u0 = static_cast<int>(fu) - reach_, v0 = static_cast<int>(fv) - reach_;
      const int u1 = u0 + side, v1 = v0 + side;
      if (u0 < 0 || v0 < 0 || u1 > nx_ || v1 > ny_) continue;
      const int covered = sum_[v1 * (nx_ + 1) + u1] - sum_[v0 * (nx_ + 1) + u1] - sum_[v1 * (nx_ + 1) + u0] +
                          sum_[v0 * (nx_ + 1) + u0];
      in += covered == side * side;
    }
    return {in, n};
  }

 private:
  static constexpr double kMaxSide = 30.0;  // metres: a car track spread wider is moving already
  int pixelOf(float c, double origin) const { return static_cast<int>(std::floor((c - origin) * inv_)); }
  double inv_;
  int reach_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int nx_ = 0, ny_ = 0;
  std::vector<int> sum_;
};

double centroidDistance(Shape shape, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // Cylinders are compared on the ground plane: the visible part of a trunk varies in height.
  return shape == Shape::Cylinder ? (a - b).head<2>().norm() : (a - b).norm();
}
}  // namespace

Cloud Track::accumulated(double max_growth) const {
  std::vector<float> width;
  if (max_growth > 0 && observations.size() >= 3)
    for (const auto& o : observations) {
      const Eigen::AlignedBox2f box = grownBox(o.points, 0.0f);
      width.push_back(o.points.empty() ? 0.0f : box.sizes().maxCoeff());
    }
  float limit = std::numeric_limits<float>::infinity();
  if (!width.empty()) {
    std::vector<float> sorted = width;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    limit = static_cast<float>(max_growth) * sorted[sorted.size() / 2];
  }
  Cloud out;
  std::size_t k = 0;
  for (const auto& o : observations) {
    if (width.empty() || width[k++] <= limit) out.insert(out.end(), o.points.begin(), o.points.end());
  }
  return out;
}

Cloud Track::freeSpace() const {
  // Observations from nearby viewpoints see through the same cells: each 0.1 m cell counted once.
  Cloud out;
  std::unordered_set<std::int64_t> seen;
  for (const auto& o : observations)
    for (const auto& q : o.free_space) {
      const std::int64_t key = (static_cast<std::int64_t>(std::floor(q.x() * 10.0f)) << 32) ^
                               (static_cast<std::int64_t>(std::floor(q.y() * 10.0f)) & 0xffffffffLL);
      if (seen.insert(key).second) out.push_back(q);
    }
  return out;
}

Eigen::Vector3d Track::viewpoint() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0;
  for (const auto& o : observations) {
    sum += static_cast<double>(o.points.size()) * o.viewpoint;
    n += static_cast<double>(o.points.size());
  }
  return n > 0 ? Eigen::Vector3d(sum / n) : last_centroid;
}

Tracker::Tracker(ClassTable classes, TrackerParams params, FitParams fit)
    : classes_(std::move(classes)), params_(params), fit_(fit) {
  for (const auto& [name, range] : params_.report_max_range_by_class) {
    const ClassInfo* c = classes_.findByName(name);
    if (!c) throw std::invalid_argument("tracker.report_max_range_by_class: no class named '" + name + "' in the class table");
    report_range_of_class_[c->id] = range;
  }
}

double Tracker::reportRange(int class_id) const {
  const auto it = report_range_of_class_.find(class_id);
  return it != report_range_of_class_.end() ? it->second : params_.report_max_range;
}

bool Tracker::exceedsClassSize(const Track& t) const {
  std::vector<cv::Point2f> pts;
  for (const auto& o : t.observations)
    for (const auto& p : o.points) pts.emplace_back(p.x(), p.y());
  return exceedsClassSize(pts, t.class_id);
}

bool Tracker::exceedsClassSize(const std::vector<cv::Point2f>& pts, int class_id) const {
  const ClassInfo& info = classes_.at(class_id);
  if (pts.size() < 3) return false;
  const cv::RotatedRect r = cv::minAreaRect(pts);
  const double len = std::max(r.size.width, r.size.height), wid = std::min(r.size.width, r.size.height);
  const double tol = params_.moving_tolerance;
  // Horizontal extents only: vertical growth comes from seeing more of a tall object.
  return len > info.size_max.x() * tol || wid > info.size_max.y() * tol;
}

bool Tracker::vacated(const Track& t, const Observation& newest) const {
  if (params_.moving_vacated_share <= 0 || newest.free_space.empty() || t.observations.empty()) return false;
  Eigen::AlignedBox2d region;  // where the earlier points lie
  for (const auto& earlier : t.observations)
    for (const auto& p : earlier.points) region.extend(p.head<2>().cast<double>());
  const FreeRaster free(newest.free_space, 0.1, params_.moving_vacated_depth, region);
  for (const auto& earlier : t.observations) {
    if (&earlier == &newest) continue;
    const auto [in, n] = free.count(earlier.points, 200);
    if (in >= params_.moving_vacated_min_points && in > params_.moving_vacated_share * n) return true;
  }
  return false;
}

bool Tracker::shifted(const Track& t, const Observation& newest, double min_interval) const {
  if (params_.moving_shift <= 0 || classes_.at(t.class_id).shape != Shape::Cuboid) return false;
  const auto min_points = static_cast<std::size_t>(std::max(1, params_.moving_shift_min_points));
  if (newest.points.size() < min_points) return false;
  const Observation* earlier = nullptr;  // the latest one at least the interval older
  for (auto it = t.observations.rbegin(); it != t.observations.rend(); ++it)
    if (secondsBetween(it->utime, newest.utime) >= min_interval) {
      earlier = &*it;
      break;
    }
  if (!earlier || secondsBetween(earlier->utime, newest.utime) > params_.moving_shift_max_interval) return false;
  if (earlier->points.size() < min_points) return false;
  const Eigen::Vector2d step = (centroidOf(newest.points) - centroidOf(earlier->points)).head<2>();
  if (!step.allFinite() || step.norm() < params_.moving_shift) return false;
  const Eigen::Vector2d u = step.normalized();
  const double q = std::clamp(params_.moving_shift_quantile, 0.0, 0.5);
  auto ends = [&](const Cloud& c) {
    std::vector<double> d;
    d.reserve(c.size());
    for (const auto& p : c) d.push_back(u.dot(p.head<2>().cast<double>()));
    const auto lo = static_cast<std::ptrdiff_t>(q * static_cast<double>(d.size() - 1));
    const auto hi = static_cast<std::ptrdiff_t>((1 - q) * static_cast<double>(d.size() - 1));
    std::nth_element(d.begin(), d.begin() + lo, d.end());
    const double a = d[lo];
    std::nth_element(d.begin(), d.begin() + hi, d.end());
    return std::pair{a, d[hi]};
  };
  const auto [lo0, hi0] = ends(earlier->points);
  const auto [lo1, hi1] = ends(newest.points);
  // The same view of one rigid body: about as many points, about as long along the shift.
  const double n0 = static_cast<double>(earlier->points.size()), n1 = static_cast<double>(newest.points.size());
  const double ratio = params_.moving_shift_similarity;
  if (std::max(n0, n1) > ratio * std::min(n0, n1)) return false;
  const double l0 = std::max(hi0 - lo0, 0.1), l1 = std::max(hi1 - lo1, 0.1);
  if (std::max(l0, l1) > ratio * std::min(l0, l1)) return false;
  // Along its length: a box seen at least as long as its class's shortest along the shift (the
  // quantiles' share of it). Not the next car of a row, seen end-on, across its width.
  if (std::min(l0, l1) < (1 - 2 * q) * classes_.at(t.class_id).size_min.x()) return false;
  return lo1 - lo0 >= params_.moving_shift && hi1 - hi0 >= params_.moving_shift;
}

void Tracker::update(const FrameInstances& frame, InputIssues& issues) {
  if (!frame.odom_pose.matrix().allFinite()) {
    issues.count("non-finite odometry pose");
    return;
  }
  // Instances per class in the odometry frame.
  struct Obs {
    int class_id;
    float confidence;
    Observation seen;
    Eigen::Vector3d centroid;
  };
  std::map<int, std::vector<Obs>> by_class;
  for (const auto& inst : frame.instances) {
    if (!classes_.find(inst.class_id)) {
      issues.count("unknown class");
      continue;
    }
    Cloud pts;
    pts.reserve(inst.points.size());
    long bad = 0;
    for (const auto& p : inst.points) {
      if (p.allFinite()) pts.push_back(p);
      else ++bad;
    }
    issues.count("non-finite point", bad);
    if (pts.empty()) {
      issues.count("empty instance");
      continue;
    }
    Obs o{inst.class_id, inst.confidence,
          {transformCloud(frame.odom_pose, subsample(pts, params_.max_points_per_observation)),
           frame.odom_pose.translation(),
           frame.utime,
           transformCloud(frame.odom_pose, subsample(inst.free_space, kFreeCellsPerPoint * params_.max_points_per_observation))},
          {}};
    if (params_.drop_oversized) {
      // Larger than the class on its own: several objects joined by the segmenter, not one
      // (added to a track it would make the track look moving).
      std::vector<cv::Point2f> xy;
      xy.reserve(o.seen.points.size());
      for (const auto& p : o.seen.points) xy.emplace_back(p.x(), p.y());
      if (exceedsClassSize(xy, inst.class_id)) {
        issues.count("instance larger than its class");
        continue;
      }
    }
    o.centroid = centroidOf(o.seen.points);
    by_class[inst.class_id].push_back(std::move(o));
  }

  // Box views on two tracks' last views: split (TrackerParams::split_distance).
  if (params_.split_distance > 0) {
    // The last views' boxes of the static box tracks seen lately, found once per frame, and their
    // points subsampled when first needed.
    std::vector<std::pair<const Track*, Eigen::AlignedBox2f>> lately;
    for (const auto& [id, t] : tracks_)
      if (!t.moving && t.missed <= kSplitMaxMissed && !t.observations.empty() && classes_.at(t.class_id).shape == Shape::Cuboid)
        lately.emplace_back(&t, grownBox(t.observations.back().points, 0.0f));
    std::map<const Track*, Cloud> last_of;
    // The nearest (by centroid, at most kSplitMaxTracks) of those tracks of a view's class whose
    // last view its box, grown by split_distance, meets; and their subsampled last views.
    auto nearTracks = [&](const Obs& o, std::vector<const Track*>& near, std::vector<const Cloud*>& lasts) {
      const Eigen::AlignedBox2f box = grownBox(o.seen.points, static_cast<float>(params_.split_distance));
      std::vector<std::pair<double, const Track*>> by_distance;
      for (const auto& [t, last_box] : lately)
        if (t->class_id == o.class_id && box.intersects(last_box))
          by_distance.emplace_back((t->last_centroid - o.centroid).head<2>().norm(), t);
      std::sort(by_distance.begin(), by_distance.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      near.clear();
      lasts.clear();
      for (std::size_t j = 0; j < by_distance.size() && j < kSplitMaxTracks; ++j) {
        const Track* t = by_distance[j].second;
        auto it = last_of.find(t);
        if (it == last_of.end()) it = last_of.emplace(t, subsample(t->observations.back().points, kSplitPointsPerTrack)).first;
        near.push_back(t);
        lasts.push_back(&it->second);
      }
    };
    std::vector<const Track*> near;
    std::vector<const Cloud*> lasts;
    for (auto& [class_id, obs] : by_class) {
      if (classes_.at(class_id).shape != Shape::Cuboid) continue;
      std::vector<Obs> out;
      for (auto& o : obs) {
        nearTracks(o, near, lasts);
        std::vector<Cloud> parts = partsOnTracks(o.seen.points, lasts, params_.split_distance, params_.split_min_points,
                                                 params_.split_min_gap);
        if (parts.empty()) {
          out.push_back(std::move(o));
          continue;
        }
        for (auto& part : parts) {
          Obs piece{o.class_id, o.confidence, o.seen, {}};
          piece.seen.points = std::move(part);
          piece.centroid = centroidOf(piece.seen.points);
          out.push_back(std::move(piece));
        }
      }
      obs = std::move(out);
      // Pieces of one car's view (the segmenter cut it, e.g. at a gap in its returns) are joined:
      // given to tracks one by one, a smaller piece would continue a neighbour's track.
      if (params_.join_share <= 0 || obs.size() < 2) continue;
      // Each piece, subsampled, and the track it alone lies on among its nearest lately seen ones.
      std::vector<Cloud> pieces;
      std::vector<std::int64_t> owner;
      for (const auto& o : obs) {
        pieces.push_back(subsample(o.seen.points, kSplitPointsPerTrack));
        nearTracks(o, near, lasts);
        const int j = soleTrack(pieces.back(), lasts, params_.split_distance, params_.join_share, params_.split_min_points);
        owner.push_back(j >= 0 ? near[j]->id : -1);
      }
      std::vector<char> gone(obs.size(), 0);
      for (const auto& group : piecesOfOneView(pieces, owner, params_.split_min_gap)) {
        Obs joined = obs[group.front()];
        for (std::size_t k = 1; k < group.size(); ++k) {
          const Observation& seen = obs[group[k]].seen;
          joined.seen.points.insert(joined.seen.points.end(), seen.points.begin(), seen.points.end());
          joined.seen.free_space.insert(joined.seen.free_space.end(), seen.free_space.begin(), seen.free_space.end());
          joined.confidence = std::max(joined.confidence, obs[group[k]].confidence);
        }
        std::vector<cv::Point2f> xy;
        for (const auto& p : joined.seen.points) xy.emplace_back(p.x(), p.y());
        if (exceedsClassSize(xy, class_id)) continue;
        joined.seen.points = subsample(joined.seen.points, params_.max_points_per_observation);
        joined.seen.free_space = subsample(joined.seen.free_space, kFreeCellsPerPoint * params_.max_points_per_observation);
        joined.centroid = centroidOf(joined.seen.points);
        obs[group.front()] = std::move(joined);
        for (std::size_t k = 1; k < group.size(); ++k) gone[group[k]] = 1;
      }
      std::vector<Obs> kept;
      for (std::size_t i = 0; i < obs.size(); ++i)
        if (!gone[i]) kept.push_back(std::move(obs[i]));
      obs = std::move(kept);
    }
  }

  std::map<std::int64_t, bool> matched;
  // Where a track is looked for in this frame (TrackerParams::moving_predict).
  auto expected = [&](const Track& t) -> Eigen::Vector3d {
    const double dt = secondsBetween(t.last_utime, frame.utime);
    if (!params_.moving_predict || !t.moving || dt <= 0 || dt > params_.moving_shift_max_interval) return t.last_centroid;
    return t.last_centroid + dt * t.velocity;
  };
  auto apply = [&](Track& t, Obs& o) {
    if (!t.moving && (vacated(t, o.seen) || shifted(t, o.seen, params_.moving_shift_interval))) t.moving = true;
    ++t.hits;
    t.missed = 0;
    t.confidence_sum += o.confidence;
    const double dt = secondsBetween(t.last_utime, o.seen.utime);
    if (t.moving && t.hits > 1 && dt > 0 && dt <= params_.moving_shift_max_interval) {
      t.velocity = (o.centroid - t.last_centroid) / dt;
      t.velocity.z() = 0;
      if (!t.velocity.allFinite()) t.velocity.setZero();
    }
    t.last_centroid = o.centroid;
    t.last_utime = o.seen.utime;
    t.class_votes[o.class_id] += std::isfinite(o.confidence) ? std::clamp(o.confidence, 1e-3f, 1.0f) : 1e-3f;
    t.class_id = std::max_element(t.class_votes.begin(), t.class_votes.end(),
                                  [](const auto& x, const auto& y) { return x.second < y.second; })->first;
    t.observations.push_back(std::move(o.seen));
    while (static_cast<int>(t.observations.size()) > params_.max_observations) t.observations.pop_front();
    if (!t.moving && exceedsClassSize(t)) t.moving = true;
    matched[t.id] = true;
  };
  // Gated Hungarian between observations and the unmatched tracks accepted by `compatible`;
  // returns the observations left over.
  auto associate = [&](std::vector<Obs> obs, const std::function<bool(const Track&)>& compatible, Shape shape, double gate) {
    std::vector<Track*> cand;
    for (auto& [id, t] : tracks_)
      if (!matched.count(id) && compatible(t)) cand.push_back(&t);
    std::vector<Obs> left;
    if (cand.empty()) return obs;
    Eigen::MatrixXd cost(obs.size(), cand.size());
    for (std::size_t i = 0; i < obs.size(); ++i)
      for (std::size_t j = 0; j < cand.size(); ++j) cost(i, j) = centroidDistance(shape, obs[i].centroid, expected(*cand[j]));
    const std::vector<int> assign = assignment::solveGatedAssignment(cost, gate);
    for (std::size_t i = 0; i < obs.size(); ++i) {
      if (assign[i] >= 0) apply(*cand[assign[i]], obs[i]);
      else left.push_back(std::move(obs[i]));
    }
    return left;
  };
  // 1. Per class. 2. Leftovers against unmatched tracks of other classes of the same shape
  // (a segmenter may call one trunk a pole in some frames; the track's class is the majority
  // of its observations).
  std::vector<Obs> leftovers;
  for (auto& [class_id, obs] : by_class) {
    const ClassInfo& info = classes_.at(class_id);
    const int cls = class_id;
    auto left = associate(std::move(obs), [cls](const Track& t) { return t.class_id == cls; }, info.shape,
                          info.association_distance * params_.gate_scale);
    for (auto& o : left) leftovers.push_back(std::move(o));
  }
  std::vector<Obs> fresh;
  for (auto& o : leftovers) {
    const ClassInfo& info = classes_.at(o.class_id);
    std::vector<Obs> one;
    one.push_back(std::move(o));
    auto left = params_.merge_same_shape
                    ? associate(std::move(one), [&](const Track& t) { return classes_.at(t.class_id).shape == info.shape; },
                                info.shape, info.association_distance * params_.gate_scale)
                    : std::move(one);
    for (auto& l : left) fresh.push_back(std::move(l));
  }
  // 3. A box that moved beyond the gate since the previous frame: its track, now moving
  // (TrackerParams::moving_shift_reach), rather than a new track. 4. New tracks for the rest.
  if (params_.moving_shift > 0 && params_.moving_shift_reach > 0) {
    std::vector<Obs> rest;
    for (auto& o : fresh) {
      Track* best = nullptr;
      double best_d = params_.moving_shift_reach;
      for (auto& [id, t] : tracks_) {
        if (matched.count(id) || t.missed > 0 || t.class_id != o.class_id || t.observations.empty()) continue;
        const double d = (t.last_centroid - o.centroid).head<2>().norm();
        if (d < best_d && shifted(t, o.seen, 0.0)) best = &t, best_d = d;
      }
      if (!best) {
        rest.push_back(std::move(o));
        continue;
      }
      best->moving = true;
      apply(*best, o);
    }
    fresh = std::move(rest);
  }
  for (auto& o : fresh) {
    Track t;
    t.id = next_id_++;
    t.class_id = o.class_id;
    apply(tracks_.emplace(t.id, t).first->second, o);
  }
  if (params_.column_merge_distance > 0)
    mergeTracks(matched, [&](const Track& a, const Track& b) {
      return classes_.at(a.class_id).shape == Shape::Cylinder && classes_.at(b.class_id).shape == Shape::Cylinder &&
             centroidDistance(Shape::Cylinder, a.last_centroid, b.last_centroid) <= params_.column_merge_distance;
    });
  if (params_.catch_all_merge_distance > 0)
    mergeTracks(matched, [&](const Track& a, const Track& b) {
      const ClassInfo &ca = classes_.at(a.class_id), &cb = classes_.at(b.class_id);
      return ca.catch_all != cb.catch_all && ca.shape == cb.shape &&
             centroidDistance(ca.shape, a.last_centroid, b.last_centroid) <= params_.catch_all_merge_distance;
    });
  splitEarlierViews(matched);
  mergeBoxTracks(matched);
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    if (!matched.count(it->first)) ++it->second.missed;
    if (it->second.missed > params_.max_missed) it = tracks_.erase(it);
    else ++it;
  }
}

void Tracker::mergeTracks(std::map<std::int64_t, bool>& matched,
                          const std::function<bool(const Track&, const Track&)>& one_object) {
  for (auto a = tracks_.begin(); a != tracks_.end(); ++a)
    for (auto b = std::next(a); b != tracks_.end();) {
      if (!one_object(a->second, b->second)) {
        ++b;
        continue;
      }
      absorb(a->second, b->second, params_.max_observations);  // the older track (lower id) takes the younger one
      if (matched.count(b->first)) matched[a->first] = true;   // seen in this frame: not missed
      b = tracks_.erase(b);
    }
}

void Tracker::splitEarlierViews(const std::map<std::int64_t, bool>& matched) {
  if (params_.split_distance <= 0) return;
  // The newest view's box of each static box track matched in this frame, grown by the reach.
  std::map<std::int64_t, Eigen::AlignedBox2f> newest;
  for (const auto& [id, t] : tracks_)
    if (matched.count(id) && !t.moving && !t.observations.empty() && classes_.at(t.class_id).shape == Shape::Cuboid)
      newest.emplace(id, grownBox(t.observations.back().points, static_cast<float>(params_.split_distance)));
  for (auto& [id_a, a] : tracks_) {
    if (!newest.count(id_a) || a.observations.size() < 2) continue;
    for (const auto& [id_b, near_b] : newest) {
      const Track& b = tracks_.at(id_b);
      if (id_b == id_a || b.class_id != a.class_id) continue;
      std::vector<Cloud> lasts;
      for (auto it = a.observations.begin(); std::next(it) != a.observations.end(); ++it) {
        if (!near_b.intersects(grownBox(it->points, 0.0f))) continue;
        if (lasts.empty())
          lasts = {subsample(a.observations.back().points, kSplitPointsPerTrack),
                   subsample(b.observations.back().points, kSplitPointsPerTrack)};
        std::vector<Cloud> parts = partsOnTracks(it->points, {&lasts[0], &lasts[1]}, params_.split_distance,
                                                 params_.split_min_points, params_.split_min_gap);
        // Parts come in the order of `lasts`, both kept: the first is a's.
        if (parts.size() == 2) it->points = std::move(parts[0]);
      }
    }
  }
}

void Tracker::mergeBoxTracks(std::map<std::int64_t, bool>& matched) {
  if (params_.box_merge_width <= 0) return;
  std::vector<cv::Point2f> pts;
  for (auto a = tracks_.begin(); a != tracks_.end(); ++a) {
    const ClassInfo& info = classes_.at(a->second.class_id);
    if (info.shape != Shape::Cuboid || a->second.moving) continue;
    for (auto b = std::next(a); b != tracks_.end();) {
      Track& older = a->second;
      Track& younger = b->second;
      if (younger.class_id != older.class_id || younger.moving ||
          (older.last_centroid - younger.last_centroid).head<2>().norm() > info.size_max.x()) {
        ++b;
        continue;
      }
      pts.clear();
      footprintSample(older, 300, pts);
      footprintSample(younger, 300, pts);
      const cv::RotatedRect rect = cv::minAreaRect(pts);
      const double length = std::max(rect.size.width, rect.size.height);
      bool merge = length <= info.size_max.x() && std::min(rect.size.width, rect.size.height) <= params_.box_merge_width;
      if (merge) {  // one holds the other: along the joint footprint's length, no longer than the longer alone
        cv::Point2f c[4];
        rect.points(c);
        cv::Point2f axis = cv::norm(c[1] - c[0]) >= cv::norm(c[2] - c[1]) ? c[1] - c[0] : c[2] - c[1];
        axis *= 1.0f / std::max(1e-6f, static_cast<float>(cv::norm(axis)));
        merge = length <= std::max(viewLength(older, axis, params_.box_merge_view_quantile),
                                   viewLength(younger, axis, params_.box_merge_view_quantile)) +
                              params_.box_merge_growth;
      }
      if (!merge) {
        ++b;
        continue;
      }
      absorb(older, younger, params_.max_observations);
      // A car driving faster than the gate leaves a track per frame, which this merge joins: the
      // joint track is moving when its last view (the younger track's) saw through where another
      // stood (either way round, the object was not in one place).
      if (!older.moving && vacated(older, older.observations.back())) older.moving = true;
      if (matched.count(b->first)) matched[a->first] = true;  // seen in this frame: not missed
      b = tracks_.erase(b);
    }
  }
}

namespace {
// Each box with an other reading takes the reading whose heading the sure boxes (no other
// reading) of its class within `radius` agree with more (otherReadingAgreesMore). Without sure
// boxes nearby it keeps its first reading.
void settleBoxReadings(std::vector<std::pair<Object, std::optional<Object>>>& fits, double radius, double fallback) {
  for (auto& [o, other] : fits) {
    if (!other) continue;
    // Boxes seen whole within `radius` vote, or within `fallback` when none is that near.
    for (double r : {radius, fallback}) {
      std::vector<double> headings;
      for (const auto& [s, s_other] : fits)
        if (!s_other && s.class_id == o.class_id && (s.position() - o.position()).head<2>().norm() <= r)
          headings.push_back(headingOf(std::get<Cuboid>(s.model)));
      if (otherReadingAgreesMore(std::get<Cuboid>(o.model), std::get<Cuboid>(other->model), headings))
        std::swap(o.model, other->model);
      if (!headings.empty()) break;
    }
  }
}
}  // namespace

std::optional<Object> Tracker::fitPoints(const Cloud& points, const Cloud& free_space, const Eigen::Vector3d& view,
                                         int class_id, std::int64_t id, int hits, double confidence_sum,
                                         const Pose& T_body_odom, std::optional<Object>* other) const {
  const Cloud free_body = transformCloud(T_body_odom, free_space);
  auto o = fitObject(transformCloud(T_body_odom, points), class_id, classes_, fit_, T_body_odom * view, nullptr, other,
                     &free_body);
  if (!o) return std::nullopt;
  o->id = id;
  o->num_observations = hits;
  o->confidence = confidence_sum / std::max(1, hits);
  if (other && *other) (*other)->id = id, (*other)->num_observations = hits, (*other)->confidence = o->confidence;
  return o;
}

namespace {

cv::RotatedRect footprintRect(const Object& o) {
  const Cuboid& c = std::get<Cuboid>(o.model);
  return cv::RotatedRect(cv::Point2f(c.pose.translation().x(), c.pose.translation().y()), cv::Size2f(c.dims.x(), c.dims.y()),
                         headingOf(c) * 180.0 / M_PI);
}

// Area (m^2) both footprints cover.
double overlapArea(const cv::RotatedRect& a, const cv::RotatedRect& b) {
  const double reach = 0.5 * (std::hypot(a.size.width, a.size.height) + std::hypot(b.size.width, b.size.height));
  std::vector<cv::Point2f> poly, hull;
  if (cv::norm(a.center - b.center) > reach || cv::rotatedRectangleIntersection(a, b, poly) == cv::INTERSECT_NONE ||
      poly.size() < 3)
    return 0.0;
  cv::convexHull(poly, hull);
  return cv::contourArea(hull);
}

}  // namespace

void Tracker::dropEllipsoidsAtOnePlace(std::vector<std::pair<Object, std::optional<Object>>>& fits) const {
  std::vector<bool> dropped(fits.size(), false);
  for (std::size_t i = 0; i < fits.size(); ++i)
    for (std::size_t j = i + 1; j < fits.size() && !dropped[i]; ++j) {
      const Object &a = fits[i].first, &b = fits[j].first;
      if (dropped[j] || a.shape() != Shape::Ellipsoid || b.shape() != Shape::Ellipsoid || !classes_.sameKind(a.class_id, b.class_id) ||
          (a.position() - b.position()).norm() > params_.ellipsoid_same_place)
        continue;
      dropped[a.num_observations < b.num_observations ? i : j] = true;
    }
  std::size_t k = 0;
  for (std::size_t i = 0; i < fits.size(); ++i)
    if (!dropped[i]) fits[k++] = std::move(fits[i]);
  fits.resize(k);
}

void Tracker::dropBoxesAcrossNeighbours(std::vector<std::pair<Object, std::optional<Object>>>& fits) const {
  const std::size_t n = fits.size();
  // The share of each box's footprint that each other box of its class covers (boxes only
  // leave, so the shares are found once); a box's cover is the sum (they stand apart).
  Eigen::MatrixXd share = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Object &a = fits[i].first, &b = fits[j].first;
      if (a.shape() != Shape::Cuboid || b.shape() != Shape::Cuboid || a.class_id != b.class_id) continue;
      const cv::RotatedRect ra = footprintRect(a), rb = footprintRect(b);
      const double area = overlapArea(ra, rb);
      share(i, j) = area / std::max(1e-9f, ra.size.area());
      share(j, i) = area / std::max(1e-9f, rb.size.area());
    }
  std::vector<bool> dropped(n, false);
  for (;;) {  // the most covered first: once it is gone, the boxes it stood on are judged without it
    double most = params_.box_across;
    std::size_t worst = n;
    for (std::size_t i = 0; i < n; ++i)
      if (!dropped[i])
        if (const double c = share.row(i).sum(); c > most) most = c, worst = i;
    if (worst == n) break;
    dropped[worst] = true;
    share.col(worst).setZero();
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (!dropped[i]) fits[k++] = std::move(fits[i]);
  fits.resize(k);
}

void Tracker::joinOverlappingBoxes(std::vector<std::pair<Object, std::optional<Object>>>& fits, const Pose& T_body_odom,
                                   bool readings) const {
  auto overlapShare = [](const cv::RotatedRect& a, const cv::RotatedRect& b) {
    return overlapArea(a, b) / std::max(1e-9f, std::min(a.size.area(), b.size.area()));
  };
  // Each entry's tracks: an entry that took another in is fitted to all of theirs.
  std::vector<std::vector<const Track*>> members(fits.size());
  for (std::size_t i = 0; i < fits.size(); ++i) members[i] = {&tracks_.at(fits[i].first.id)};
  for (std::size_t a = 0; a < fits.size(); ++a) {
    if (members[a].empty() || fits[a].first.shape() != Shape::Cuboid) continue;
    for (std::size_t b = a + 1; b < fits.size(); ++b) {
      if (members[b].empty() || fits[b].first.class_id != fits[a].first.class_id) continue;
      // A box whose length went unseen may be read the other way: two boxes on one centre (within
      // box_same_centre) are one object when a pair of their readings overlaps so (one car tracked
      // twice, each track reading it its own way).
      double share = overlapShare(footprintRect(fits[a].first), footprintRect(fits[b].first));
      if ((fits[a].first.position() - fits[b].first.position()).head<2>().norm() < params_.box_same_centre)
        for (const Object* x : {&fits[a].first, fits[a].second ? &*fits[a].second : nullptr})
          for (const Object* y : {&fits[b].first, fits[b].second ? &*fits[b].second : nullptr})
            if (x && y) share = std::max(share, overlapShare(footprintRect(*x), footprintRect(*y)));
      if (share <= params_.box_overlap) continue;
      std::vector<const Track*> both = members[a];
      both.insert(both.end(), members[b].begin(), members[b].end());
      Cloud points, free;
      Eigen::Vector3d view = Eigen::Vector3d::Zero();  // the tracks' viewpoints weighted by their points
      int hits = 0;
      double confidence_sum = 0;
      for (const Track* t : both) {
        const Cloud c = t->accumulated();
        view += static_cast<double>(c.size()) * t->viewpoint();
        points.insert(points.end(), c.begin(), c.end());
        const Cloud f = t->freeSpace();
        free.insert(free.end(), f.begin(), f.end());
        hits += t->hits, confidence_sum += t->confidence_sum;
      }
      view /= std::max<double>(1.0, static_cast<double>(points.size()));
      std::optional<Object> other;
      auto o = fitPoints(points, free, view, fits[a].first.class_id, fits[a].first.id, hits, confidence_sum, T_body_odom,
                         readings ? &other : nullptr);
      if (!o) continue;
      fits[a] = {std::move(*o), std::move(other)};
      members[a] = std::move(both);
      members[b].clear();
    }
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < fits.size(); ++i)
    if (!members[i].empty()) fits[k++] = std::move(fits[i]);
  fits.resize(k);
}

std::vector<Object> Tracker::objectsInBody(const Pose& T_odom_body, int frames_since_report) const {
  std::vector<std::pair<Object, std::optional<Object>>> fits;  // the fit and its other reading, if any
  const Pose T_body_odom = T_odom_body.inverse();
  const int max_missed = std::max(params_.report_max_missed, frames_since_report - 1);
  const bool readings = params_.parallel_radius > 0;
  for (const auto& [id, t] : tracks_) {
    if (t.moving || t.hits < params_.min_age || t.missed > max_missed) continue;
    // Completion away from where the points were seen (not from the current pose: the robot
    // may have passed the object since).
    std::optional<Object> other;
    const bool ellipsoid = classes_.at(t.class_id).shape == Shape::Ellipsoid;
    auto o = fitPoints(t.accumulated(ellipsoid ? params_.ellipsoid_view_growth : 0.0), t.freeSpace(), t.viewpoint(),
                       t.class_id, id, t.hits, t.confidence_sum, T_body_odom, readings ? &other : nullptr);
    if (o) fits.emplace_back(std::move(*o), std::move(other));
  }
  // Readings are settled by the parallel neighbours before overlapping boxes are joined: two
  // noses side by side, each read across, overlap; settled along their neighbours they stand
  // apart. A joint box is settled in turn.
  if (readings) settleBoxReadings(fits, params_.parallel_radius, params_.parallel_fallback_radius);
  const std::size_t before = fits.size();
  if (params_.box_overlap > 0) joinOverlappingBoxes(fits, T_body_odom, readings);
  if (readings && fits.size() < before) settleBoxReadings(fits, params_.parallel_radius, params_.parallel_fallback_radius);
  if (params_.box_across > 0) dropBoxesAcrossNeighbours(fits);
  if (params_.ellipsoid_same_place > 0) dropEllipsoidsAtOnePlace(fits);
  std::vector<Object> out;
  out.reserve(fits.size());
  for (auto& [o, other] : fits) {
    if (const double range = reportRange(o.class_id); range > 0 && o.position().head<2>().norm() > range) continue;
    if (other)
      if (const auto* box = std::get_if<Cuboid>(&other->model)) o.other_reading = *box;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace slide::frontend
