#pragma once
// What sharing a map costs against sharing the raw data: each robot of a scenario builds its
// own object map (the back-end on its bundles alone), encoded as the team bus sends it
// (team::encodeMap), next to the LiDAR points the robot recorded over the same stretch.
#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "graph_scenario/scenario.h"

namespace slide {

struct RobotMapSize {
  int robot = 0;
  int objects = 0;         // confirmed landmarks of its own map
  std::size_t map_bytes = 0;
  long frames = 0;         // LiDAR frames it drove through
  double raw_bytes = 0;    // frames x points per scan x 16 B (x, y, z, intensity as float32)
};

// Each robot's own map; frames counted on the sequence's LiDAR poses (`lidar`, from which the
// robot's key poses were taken). Throws std::runtime_error when a robot's key poses are not
// found among them.
std::vector<RobotMapSize> robotMapSizes(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                                        const std::vector<Pose>& lidar, double points_per_scan);

// Mean points per scan of the KITTI-format scans (float32 x, y, z, intensity) in `dir`.
// Throws std::runtime_error naming the folder when it holds no .bin scan.
double meanPointsPerScan(const std::string& dir);

}  // namespace slide
