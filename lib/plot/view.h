#pragma once
// How 3D world points become 2D picture coordinates: an orthographic view from a direction
// given by azimuth and elevation. The top view looks straight down (x right, y up).
#include <Eigen/Core>

namespace slide::plot {

struct View {
  double azimuth_deg = -90;   // direction of the viewer around z, from +x (top view: -90)
  double elevation_deg = 90;  // above the horizon; 90 looks straight down

  static View top() { return {}; }
  static View oblique(double azimuth_deg = -60, double elevation_deg = 35) { return {azimuth_deg, elevation_deg}; }
  bool isTop() const { return elevation_deg >= 89.999; }

  // Unit vector from the scene towards the viewer.
  Eigen::Vector3d towardsViewer() const;
  // Picture-plane coordinates (u right, v up), in metres.
  Eigen::Vector2d project(const Eigen::Vector3d& p) const;
  // Larger is farther from the viewer (for painter's ordering).
  double depth(const Eigen::Vector3d& p) const { return -towardsViewer().dot(p); }
};

}  // namespace slide::plot
