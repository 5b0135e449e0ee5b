#pragma once
// Object-level worlds for the place benchmark: procedural forest, urban streets and indoor
// rooms, KITTI poles along the real trajectories, and the robots' maps of them (each in the
// robot's own frame, with noise and missed objects). Landmark::index holds the world id.
#include <functional>
#include <random>
#include <string>

#include "place/map_perturb.h"

namespace slide::bench_place {

using World = std::vector<place::Landmark>;

// A robot's map: its landmarks in its own frame and the pose of that frame in the world.
struct RobotMap {
  std::vector<place::Landmark> lms;
  Pose T_w_r = Pose::Identity();
};

// Truth T_a_b between two robots' frames.
inline Pose truthBetween(const RobotMap& a, const RobotMap& b) { return a.T_w_r.inverse() * b.T_w_r; }

// Trunks (class 71) as a Poisson process of `density` per square metre over [0,w] x [0,h].
World forestWorld(double w, double h, double density, std::mt19937& rng);
// Streets on a 60 m grid over w x w: parked cars (10), poles (80), trees (71), other (0).
World urbanWorld(double w, std::mt19937& rng);
// Offices in a grid of rooms: tables (2), chairs (1) around them, monitors (3) on them.
World indoorWorld(int rooms_x, int rooms_y, std::mt19937& rng);

// The world landmarks for which `visible` holds, seen from frame T_w_r with perturbation p.
RobotMap observe(const World& world, const std::function<bool(const place::Landmark&)>& visible, const Pose& T_w_r,
                 const place::PerturbParams& p, std::mt19937& rng);

// A random robot frame: position within `spread` metres of `around`, any yaw, small z.
Pose randomFrame(const Eigen::Vector2d& around, double spread, std::mt19937& rng);

// KITTI: pole map (x, y in the first LiDAR frame) and LiDAR poses of a sequence.
struct KittiSequence {
  World poles;
  std::vector<Pose> poses;  // LiDAR poses in the first scan's frame
};
// Throws std::runtime_error naming the file when the data cannot be read.
KittiSequence loadKitti(const std::string& data_dir, const std::string& seq);
// The robot driving frames [first, last]: poles within `range` of any of its poses, in the
// frame of its first pose.
RobotMap kittiRobot(const KittiSequence& kitti, int first, int last, double range, const place::PerturbParams& p,
                    std::mt19937& rng);

// `lms` as an object map text file (what ./slide match reads; the default class table).
void writeLandmarks(const std::string& path, const std::vector<place::Landmark>& lms);

// Number of world ids present in both maps.
std::size_t sharedLandmarks(const RobotMap& a, const RobotMap& b);

}  // namespace slide::bench_place
