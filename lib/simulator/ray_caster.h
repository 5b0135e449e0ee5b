#pragma once
// Nearest-hit ray casting against a world frozen at one time: its objects (labelled with
// class and instance), scenery and ground. Objects are bucketed in a 2-D grid over x, y and
// rays walk the grid cells they cross (Amanatides-Woo), testing only the shapes there.
#include <cstdint>
#include <vector>

#include "simulator/world.h"

namespace slide::simulator {

struct RayHit {
  double range = 0;       // metres along the ray
  uint16_t semantic = 0;  // SemanticKITTI-style label
  uint16_t instance = 0;  // object id (index + 1), 0 for scenery and ground
};

class RayCaster {
 public:
  // Freezes `world` at time t (moving objects placed at t). cell_size in metres.
  explicit RayCaster(const World& world, double t = 0.0, double cell_size = 4.0);

  // Nearest surface along the unit ray (origin, dir) closer than max_range.
  bool cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double max_range, RayHit* hit) const;

  std::size_t numPrimitives() const { return prims_.size(); }

 private:
  friend class OriginView;
  enum class Kind : uint8_t { Cylinder, Box, Ellipsoid };
  struct Primitive {
    Kind kind;
    uint16_t semantic, instance;
    Eigen::Vector3d a, b, c;   // cylinder: root, axis, (radius, length, -); box: centre, half, -; ellipsoid: centre, semi, -
    Eigen::Matrix3d R;         // box: world-to-box rotation
    double zmin, zmax;
  };
  void add(const ObjectModel& m, uint16_t semantic, uint16_t instance);
  double intersect(const Primitive& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) const;

  Terrain terrain_;
  std::vector<Primitive> prims_;
  std::vector<Eigen::AlignedBox2d> boxes_;
  double cell_ = 2.0;
  Eigen::Vector2d grid_min_ = Eigen::Vector2d::Zero();
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_;  // CSR: cell i holds cell_items_[cell_start_[i] .. cell_start_[i+1])
  struct CellItem {
    uint32_t prim;
    float zmin, zmax;  // copied from the primitive so the z test stays in cache
  };
  std::vector<CellItem> cell_items_;
  double scene_zmax_ = 0;
};

// Many rays from one origin (a LiDAR sweep, a camera frame): the shapes are binned by
// azimuth around the origin and sorted by horizontal distance, so a ray tests only the
// shapes in its direction, nearest first, and stops at the first hit closer than the rest.
// Gives the same hits as RayCaster::cast.
class OriginView {
 public:
  OriginView(const RayCaster& caster, const Eigen::Vector3d& origin, double max_range, int bins = 4096);
  bool cast(const Eigen::Vector3d& dir, double max_range, RayHit* hit) const;

 private:
  struct Entry {
    uint32_t prim;
    float dmin, dmax;  // horizontal distance range of the shape from the origin
    float zmin, zmax;
  };
  // First ground hit of a ray with horizontal direction bin `gbin` and rise per metre `slope`.
  double groundHit(const Eigen::Vector3d& d, double h, double slope, double max_range, int gbin) const;

  const RayCaster& caster_;
  Eigen::Vector3d origin_;
  int bins_;
  std::vector<uint32_t> start_;  // CSR over bins
  std::vector<Entry> entries_;
  // Uneven ground seen from the origin: per azimuth bin, at horizontal distances radii_[j],
  // the running maximum over k <= j of the ground's elevation slope (h_k - z_o) / r_k. A ray
  // of slope m first meets the ground where that maximum first reaches m (binary search).
  int ground_bins_ = 0;
  std::vector<double> radii_;
  std::vector<float> ground_slope_max_;  // ground_bins_ x radii_.size()
};

}  // namespace slide::simulator
