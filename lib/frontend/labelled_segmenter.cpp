#include "frontend/labelled_segmenter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_set>
#include <opencv2/imgproc.hpp>

#include "frontend/azimuth.h"
#include "frontend/cell_key.h"
#include "frontend/point_stats.h"
#include "geometry/pose.h"

namespace slide::frontend {

namespace {
// The lowest point labelled ground per cell of a horizontal grid over the scan's ground within
// max_range (horizontally; a stray far return must not size the grid).
class LabelledGround {
 public:
  LabelledGround(const io::LabelledScan& scan, const std::vector<int>& ground_labels, double cell, double max_range)
      : inv_(1.0 / cell) {
    std::vector<int> idx;
    const double r2 = max_range * max_range;
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const auto& q = scan.xyz[i];
      if (q.allFinite() && double(q.x()) * q.x() + double(q.y()) * q.y() <= r2 &&
          std::find(ground_labels.begin(), ground_labels.end(), static_cast<int>(scan.semantic[i])) != ground_labels.end())
        idx.push_back(static_cast<int>(i));
    }
    if (idx.empty()) return;
    x0_ = y0_ = std::numeric_limits<double>::infinity();
    double x1 = -x0_, y1 = -y0_;
    for (int i : idx) {
      x0_ = std::min(x0_, double(scan.xyz[i].x())), x1 = std::max(x1, double(scan.xyz[i].x()));
      y0_ = std::min(y0_, double(scan.xyz[i].y())), y1 = std::max(y1, double(scan.xyz[i].y()));
    }
    nx_ = static_cast<int>((x1 - x0_) * inv_) + 1, ny_ = static_cast<int>((y1 - y0_) * inv_) + 1;
    low_.assign(static_cast<std::size_t>(nx_) * ny_, std::numeric_limits<float>::infinity());
    for (int i : idx) {
      float& m = low_[cellOf(scan.xyz[i].x(), scan.xyz[i].y())];
      m = std::min(m, scan.xyz[i].z());
    }
  }
  // The lowest ground in the point's cell and the 8 around it; +inf when there is none.
  float lowestNear(const Eigen::Vector3f& p) const {
    float m = std::numeric_limits<float>::infinity();
    const int cx = static_cast<int>(std::floor((p.x() - x0_) * inv_)), cy = static_cast<int>(std::floor((p.y() - y0_) * inv_));
    for (int y = std::max(0, cy - 1); y <= std::min(ny_ - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(nx_ - 1, cx + 1); ++x) m = std::min(m, low_[y * nx_ + x]);
    return m;
  }

 private:
  std::size_t cellOf(float x, float y) const {
    return static_cast<std::size_t>(static_cast<int>((y - y0_) * inv_)) * nx_ + static_cast<int>((x - x0_) * inv_);
  }
  double inv_, x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<float> low_;
};

// Metres a cluster's x-y box is grown by when another's points are tested for lying in it
// (LabelledSegmenterParams::EllipsoidJoin::stacked_overlap): the returns' own scatter.
constexpr float kStackedMargin = 0.05f;
// Pairs of one class's clusters whose azimuth gap is searched, per class and scan: each search
// reads the whole scan, and a hostile scan may hold thousands of clusters in reach of each other.
constexpr int kMaxGapSearches = 64;

// Azimuth and horizontal range of the returns of a scan, each computed when first asked for.
class PolarScan {
 public:
  explicit PolarScan(const std::vector<Eigen::Vector3f>& xyz) : xyz_(xyz) {}
  double azimuth(int i) { return at(i).first; }
  double range(int i) { return at(i).second; }
  std::size_t size() const { return xyz_.size(); }
  const Eigen::Vector3f& point(int i) const { return xyz_[i]; }

 private:
  const std::pair<float, float>& at(int i) {
    if (polar_.empty()) polar_.assign(xyz_.size(), {std::numeric_limits<float>::quiet_NaN(), 0.0f});
    auto& a = polar_[i];
    if (std::isnan(a.first)) a = {azimuthOf(xyz_[i].y(), xyz_[i].x()), std::hypot(xyz_[i].x(), xyz_[i].y())};
    return a;
  }
  const std::vector<Eigen::Vector3f>& xyz_;
  std::vector<std::pair<float, float>> polar_;
};

// One cluster of a class, with its x-y box.
struct Piece {
  std::vector<int> points;
  Eigen::AlignedBox2f box;
};

// Whether pieces a and b of one class are one object seen in two
// (LabelledSegmenterParams::EllipsoidJoin): near each other and together within the class's
// size, and either one above the other or apart in azimuth with the returns in that azimuth gap,
// at their height, nearer than both. `gap_searches` counts the scans read for the latter.
bool onePieceOfTheOther(PolarScan& scan, const Piece& a, const Piece& b, const ClassInfo& info,
                        const LabelledSegmenterParams::EllipsoidJoin& p, int& gap_searches) {
  if (a.box.exteriorDistance(b.box) > p.max_gap) return false;
  std::vector<cv::Point2f> xy;
  xy.reserve(a.points.size() + b.points.size());
  for (const Piece* c : {&a, &b})
    for (int i : c->points) xy.emplace_back(scan.point(i).x(), scan.point(i).y());
  const cv::Size2f r = cv::minAreaRect(xy).size;
  if (std::max(r.width, r.height) > info.size_max.x() || std::min(r.width, r.height) > info.size_max.y()) return false;
  if (p.stacked_overlap > 0) {  // the smaller's points within the other's box (a back is a thin slab)
    const bool a_smaller = a.points.size() <= b.points.size();
    const Piece& small = a_smaller ? a : b;
    Eigen::AlignedBox2f other = a_smaller ? b.box : a.box;
    other.min().array() -= kStackedMargin, other.max().array() += kStackedMargin;
    int inside = 0;
    for (int i : small.points) inside += other.contains(scan.point(i).head<2>());
    if (inside >= p.stacked_overlap * static_cast<double>(small.points.size())) return true;
  }
  if (gap_searches >= kMaxGapSearches) return false;
  ++gap_searches;
  // Azimuths relative to the middle of both boxes (a piece of furniture spans far less than half a turn).
  const Eigen::Vector2f centre = a.box.merged(b.box).center();
  const double mid = azimuthOf(centre.y(), centre.x());
  float z_lo = std::numeric_limits<float>::infinity(), z_hi = -z_lo;
  auto span = [&](const Piece& c, double& lo, double& hi, double& range) {
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::vector<double> ranges;
    for (int i : c.points) {
      const double az = wrapAngle(scan.azimuth(i) - mid);
      lo = std::min(lo, az), hi = std::max(hi, az);
      ranges.push_back(scan.range(i));
      z_lo = std::min(z_lo, scan.point(i).z()), z_hi = std::max(z_hi, scan.point(i).z());
    }
    range = quantileInPlace(ranges, 0.5);
  };
  double lo_a, hi_a, range_a, lo_b, hi_b, range_b;
  span(a, lo_a, hi_a, range_a);
  span(b, lo_b, hi_b, range_b);
  const double gap_lo = hi_a < lo_b ? hi_a : hi_b, gap_hi = hi_a < lo_b ? lo_b : lo_a;
  if (gap_hi <= gap_lo) return false;  // they overlap in azimuth
  const double nearer = std::min(range_a, range_b) - p.min_nearer;
  int in_gap = 0, in_front = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& q = scan.point(static_cast<int>(i));
    if (!q.allFinite() || q.z() < z_lo || q.z() > z_hi) continue;
    const double az = wrapAngle(scan.azimuth(static_cast<int>(i)) - mid);
    if (az <= gap_lo || az >= gap_hi) continue;
    ++in_gap;
    in_front += scan.range(static_cast<int>(i)) < nearer;
  }
  return in_gap >= p.min_returns && in_front >= p.min_share * in_gap;
}

// Clusters of one ellipsoid class, joined where onePieceOfTheOther says they are one object.
std::vector<std::vector<int>> joinPieces(PolarScan& scan, std::vector<std::vector<int>> clusters, const ClassInfo& info,
                                         const LabelledSegmenterParams::EllipsoidJoin& p) {
  std::vector<Piece> pieces(clusters.size());
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    pieces[k].points = std::move(clusters[k]);
    for (int i : pieces[k].points) pieces[k].box.extend(scan.point(i).head<2>());
  }
  std::vector<int> root(pieces.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = static_cast<int>(i);
  auto find = [&](int i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  int gap_searches = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const int ri = find(static_cast<int>(i)), rj = find(static_cast<int>(j));
      if (ri != rj && onePieceOfTheOther(scan, pieces[i], pieces[j], info, p, gap_searches)) root[rj] = ri;
    }
  std::vector<std::vector<int>> out;
  std::map<int, std::size_t> slot;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto [it, added] = slot.emplace(find(static_cast<int>(i)), out.size());
    if (added) out.emplace_back();
    out[it->second].insert(out[it->second].end(), pieces[i].points.begin(), pieces[i].points.end());
  }
  return out;
}

// The cells (side `cell`) that hold points of a named class (LabelledSegmenterParams::
// CatchAllDebris); empty when cell is 0 or no catch-all point is there to test.
class NamedCells {
 public:
  NamedCells() = default;
  NamedCells(const Cloud& xyz, const std::vector<int>& class_of, const ClassTable& classes, double cell) : inv_(1.0 / cell) {
    std::map<int, bool> catch_all;  // class id -> catch-all, looked up once per class
    for (int c : class_of)
      if (c >= 0 && !catch_all.count(c)) catch_all[c] = classes.at(c).catch_all;
    if (std::none_of(catch_all.begin(), catch_all.end(), [](const auto& c) { return c.second; })) return;
    for (std::size_t i = 0; i < xyz.size(); ++i)
      if (class_of[i] >= 0 && !catch_all.at(class_of[i]))
        if (const auto c = cellOf(xyz[i], inv_)) cells_.insert(cellKey((*c)[0], (*c)[1], (*c)[2]));
  }
  // Share of `cluster`'s points with a named point in their cell or a neighbouring one.
  double shareBeside(const Cloud& xyz, const std::vector<int>& cluster) const {
    if (cells_.empty() || cluster.empty()) return 0.0;
    int beside = 0;
    for (int i : cluster) {
      const auto c = cellOf(xyz[i], inv_);
      bool hit = false;
      for (int dx = -1; c && dx <= 1 && !hit; ++dx)
        for (int dy = -1; dy <= 1 && !hit; ++dy)
          for (int dz = -1; dz <= 1 && !hit; ++dz) hit = cells_.count(cellKey((*c)[0] + dx, (*c)[1] + dy, (*c)[2] + dz)) > 0;
      beside += hit;
    }
    return static_cast<double>(beside) / static_cast<double>(cluster.size());
  }

 private:
  double inv_ = 0.0;
  std::unordered_set<std::int64_t> cells_;
};

NamedCells namedCells(const Cloud& xyz, const std::vector<int>& class_of, const ClassTable& classes, double cell) {
  return cell > 0 ? NamedCells(xyz, class_of, classes, cell) : NamedCells();
}
}  // namespace

LabelledSegmenter::LabelledSegmenter(ClassTable classes, LabelledSegmenterParams params)
    : classes_(std::move(classes)), params_(std::move(params)) {
  for (const auto& [name, cell] : params_.cluster_cell_by_class) {
    const ClassInfo* c = classes_.findByName(name);
    if (!c) throw std::invalid_argument("cluster_cell_by_class: no class named '" + name + "' in the class table");
    cell_of_class_[c->id] = cell;
    // Cylinder classes clustered together (merge_cylinders) take the finest of their cells.
    if (c->shape == Shape::Cylinder && (cylinder_cell_ <= 0 || cell < cylinder_cell_)) cylinder_cell_ = cell;
  }
}

std::vector<Instance> LabelledSegmenter::segment(const io::LabelledScan& scan, InputIssues& issues) const {
  if (scan.size() == 0) {
    issues.count("empty scan");
    return {};
  }
  if (!scan.hasLabels() || scan.semantic.size() != scan.size()) {
    issues.count("scan without labels");
    return {};
  }
  const double r2 = params_.max_range * params_.max_range;
  std::map<int, int> class_of_label;  // cache of the class-table lookup
  auto classOfLabel = [&](int label) {
    auto it = class_of_label.find(label);
    if (it == class_of_label.end()) it = class_of_label.emplace(label, classes_.fromSemanticKitti(label).value_or(-1)).first;
    return it->second;
  };
  const std::vector<uint16_t> labels =
      voteLabels(scan, [&](uint16_t l) { return classOfLabel(l) >= 0; }, {params_.vote_cell, params_.max_range});
  // Clustering group of each class: the class itself, or -1 for every cylinder class.
  std::map<int, std::vector<int>> groups;   // group -> point indices
  std::vector<int> class_of(scan.size(), -1);
  std::optional<LabelledGround> ground;     // built when a cuboid class shows up
  long bad = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const auto& p = scan.xyz[i];
    if (!p.allFinite()) {
      ++bad;
      continue;
    }
    if (double(p.x()) * p.x() + double(p.y()) * p.y() > r2) continue;
    const int cls = classOfLabel(labels[i]);
    if (cls < 0) continue;
    const Shape shape = classes_.at(cls).shape;
    if (shape == Shape::Cuboid && params_.cuboid_ground_strip > 0) {
      if (!ground) ground.emplace(scan, params_.ground_labels, params_.ground_cell, params_.max_range);
      const float g = ground->lowestNear(p);
      if (std::isfinite(g) && p.z() - g <= params_.cuboid_ground_strip) continue;
    }
    class_of[i] = cls;
    const bool cylinder = shape == Shape::Cylinder;
    groups[params_.merge_cylinders && cylinder ? -1 : cls].push_back(static_cast<int>(i));
  }
  issues.count("non-finite point", bad);
  const NamedCells named = namedCells(scan.xyz, class_of, classes_, params_.catch_all_debris.radius);

  std::vector<Instance> out;
  std::optional<FreeSpace> free;  // built when a cuboid-class instance is emitted
  PolarScan polar(scan.xyz);      // filled when furniture pieces are tested
  for (const auto& [group, idx] : groups) {
    GridClusterParams cp = params_.cluster;
    // Columns are vertical: cluster their points on x, y so a trunk split by occlusion or
    // bled labels in the middle stays one object.
    cp.planar = group == -1 || (group >= 0 && classes_.at(group).shape == Shape::Cylinder);
    if (const auto it = cell_of_class_.find(group); it != cell_of_class_.end()) cp.cell = it->second;
    if (group == -1 && cylinder_cell_ > 0) cp.cell = cylinder_cell_;
    std::vector<std::vector<int>> clusters = clusterGrid(scan.xyz, idx, cp);
    if (group >= 0 && classes_.at(group).shape == Shape::Cuboid && params_.min_split_cell < cp.cell) {
      // Boxes parked a few decimetres apart join at cp.cell: a cluster whose footprint is
      // larger than the class is clustered again on cells half as large (down to min_split_cell).
      const ClassInfo& info = classes_.at(group);
      std::vector<std::vector<int>> kept;
      std::vector<std::pair<std::vector<int>, double>> todo;
      for (auto& c : clusters) todo.emplace_back(std::move(c), cp.cell);
      for (std::size_t k = 0; k < todo.size(); ++k) {
        auto [c, cell] = std::move(todo[k]);
        if (auto parts = splitAtNotch(scan.xyz, c, params_.notch)) {
          for (auto* part : {&parts->first, &parts->second})
            if (static_cast<int>(part->size()) >= cp.min_points) todo.emplace_back(std::move(*part), cell);
          continue;
        }
        std::vector<cv::Point2f> xy;
        xy.reserve(c.size());
        for (int i : c) xy.emplace_back(scan.xyz[i].x(), scan.xyz[i].y());
        const cv::Size2f r = cv::minAreaRect(xy).size;
        const bool oversized = std::max(r.width, r.height) > info.size_max.x() || std::min(r.width, r.height) > info.size_max.y();
        // Car-sized, but falling apart on gap_cluster cells (an end face joined to a stripe of the
        // next car's side seen through the gap): each part is a cluster of its own. The gap
        // between two cars is a vertical slot: clustered on the footprint, where a far car's
        // faces do not fall into one strip per beam, each under gap_cluster.min_points.
        if (!oversized && params_.gap_cluster.cell > 0 && cell > params_.gap_cluster.cell + 1e-9) {
          auto parts = clusterGrid(scan.xyz, c, {params_.gap_cluster.cell, true, params_.gap_cluster.min_points});
          if (parts.size() >= 2) {
            for (auto& part : parts) todo.emplace_back(std::move(part), params_.gap_cluster.cell);
            continue;
          }
        }
        if (!oversized || 0.5 * cell < params_.min_split_cell - 1e-9) {
          kept.push_back(std::move(c));
          continue;
        }
        for (auto& part : clusterGrid(scan.xyz, c, {0.5 * cell, false, cp.min_points})) todo.emplace_back(std::move(part), 0.5 * cell);
      }
      clusters = std::move(kept);
    }
    if (group >= 0 && classes_.at(group).shape == Shape::Ellipsoid && params_.ellipsoid_join.max_gap > 0 && clusters.size() >= 2)
      clusters = joinPieces(polar, std::move(clusters), classes_.at(group), params_.ellipsoid_join);
    const bool catch_all = group >= 0 && classes_.at(group).catch_all;
    for (const auto& cluster : clusters) {
      if (static_cast<int>(cluster.size()) < params_.min_points) continue;
      if (catch_all && named.shareBeside(scan.xyz, cluster) > params_.catch_all_debris.max_share) continue;
      std::map<int, int> votes;
      for (int i : cluster) ++votes[class_of[i]];
      int best = group, most = -1;
      for (const auto& [c, n] : votes)
        if (n > most) best = c, most = n;
      // A flat patch (ground or a roof labelled as an object) is no object: the cluster must
      // stand at least min_height_fraction of its class's smallest height.
      float z_lo = 1e9f, z_hi = -1e9f;
      for (int i : cluster) z_lo = std::min(z_lo, scan.xyz[i].z()), z_hi = std::max(z_hi, scan.xyz[i].z());
      if (z_hi - z_lo < params_.min_height_fraction * classes_.at(best).size_min.z()) continue;
      Instance inst;
      inst.id = static_cast<int>(out.size()) + 1;
      inst.class_id = best;
      if (classes_.at(best).catch_all) inst.confidence = static_cast<float>(params_.other_confidence);
      inst.points.reserve(cluster.size());
      for (int i : cluster) inst.points.push_back(scan.xyz[i]);
      const ClassInfo& info = classes_.at(best);
      if (info.shape == Shape::Cuboid && params_.free_space.cell > 0) {
        if (!ground) ground.emplace(scan, params_.ground_labels, params_.ground_cell, params_.max_range);
        std::vector<double> g;
        for (int i : cluster)
          if (const float z = ground->lowestNear(scan.xyz[i]); std::isfinite(z)) g.push_back(z);
        if (!free) free.emplace(scan.xyz, params_.free_space);
        const float ground_z = g.empty() ? z_lo : static_cast<float>(quantileInPlace(g, 0.5));
        inst.free_space = free->near(cluster, ground_z, info.typicalSize().x());
      }
      out.push_back(std::move(inst));
    }
  }
  return out;
}

}  // namespace slide::frontend
