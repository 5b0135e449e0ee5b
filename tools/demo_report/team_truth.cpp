#include "team_truth.h"

#include <stdexcept>

#include "config/config.h"
#include "io/ground_truth_objects.h"
#include "io/robot_dataset.h"

namespace slide {

const RobotTruth& TeamTruth::robot(int id) const {
  for (const RobotTruth& r : robots)
    if (r.robot == id) return r;
  throw std::out_of_range("no ground truth for robot " + std::to_string(id));
}

Pose TeamTruth::T_a_b(int a, int b) const { return robot(a).T_world_odom.inverse() * robot(b).T_world_odom; }

TeamTruth readTeamTruth(const std::string& data_dir, const std::vector<int>& robots) {
  TeamTruth truth;
  for (int id : robots) {
    const std::string dir = data_dir + "/robot" + std::to_string(id);
    const io::RobotDataset ds = io::openRobotDataset(dir);
    if (ds.ground_truth.empty() || ds.odometry.empty())
      throw std::runtime_error(dir + ": needs groundtruth.txt and odom.txt to evaluate the run");
    RobotTruth r;
    r.robot = id;
    r.ground_truth = ds.ground_truth;
    r.odometry = ds.odometry;
    r.T_world_odom = ds.ground_truth.front().pose * ds.odometry.front().pose.inverse();
    const ConfigNode yaml = ConfigNode::load(dir + "/robot.yaml");
    r.platform = std::string(yaml.get<bool>("aerial", false) ? "aerial " : "ground ") +
                 (ds.sensor == io::RobotDataset::Sensor::Rgbd ? "RGBD" : "LiDAR");
    for (std::size_t i = 1; i < ds.ground_truth.size(); ++i)
      r.path_length_m += (ds.ground_truth[i].pose.translation() - ds.ground_truth[i - 1].pose.translation()).norm();
    truth.robots.push_back(r);
  }
  for (const io::GroundTruthObject& g : io::readGroundTruthObjects(data_dir + "/objects.csv"))
    if (!g.moving()) truth.objects.push_back(g.object);
  return truth;
}

}  // namespace slide
