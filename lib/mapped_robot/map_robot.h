#pragma once
// One simulated robot mapped the way the daemons would map it, in one process: every frame of
// its route is rendered by its sensor (lib/simulator), segmented (labelled LiDAR segmentation or
// RGBD masks), tracked into key-pose bundles (lib/frontend) and optimised (lib/backend, the
// robot alone). The result is its object map in its own odometry frame (its first pose).
#include <optional>
#include <vector>

#include "backend/backend_config.h"
#include "frontend/frontend_config.h"
#include "emulator/detection_emulator.h"
#include "objects/class_table.h"
#include "simulator/scenario.h"
#include "mapped_robot/sensor_rig.h"

namespace slide::mapped_robot {

struct RobotMapping {
  std::vector<Object> objects;       // confirmed landmarks, robot's odometry frame
  int frames = 0, keyposes = 0, rejected_bundles = 0;
  long raw_points = 0;               // LiDAR points or valid depth pixels rendered
  long input_issues = 0;
  double sim_cpu_s = 0, frontend_cpu_s = 0, backend_cpu_s = 0;  // thread CPU time per stage
};

struct MappingSetup {
  ClassTable classes;
  frontend::FrontendConfig frontend;
  backend::BackendConfig backend;
  std::uint64_t seed = 1;            // sensor noise (frameRng(seed, robot, frame))
  // Detections the front-end sees: the emulator's (a learned detector's errors; the default
  // of the benchmarks) when set, else the simulator's ground-truth labels / masks (an oracle).
  std::optional<emulator::DetectionEmulatorConfig> emulator;
};

// Maps robot `robot` (index into sc.robots) carrying `rig`. Throws std::out_of_range for a
// bad index and std::invalid_argument for an unknown sensor model.
RobotMapping mapRobot(const simulator::Scenario& sc, int robot, const SensorRig& rig, const MappingSetup& setup);

}  // namespace slide::mapped_robot
