#include "bag_options.h"

#include <cstdio>

#include "io/ros_bag.h"

namespace slide {

namespace {
struct Field {
  const char* flag;
  const char* key;
  std::string io::BagOptions::*member;
  const char* help;
};
const Field kFields[] = {
    {"--cloud-topic", "cloud_topic", &io::BagOptions::cloud_topic, "Bag: sensor_msgs/PointCloud2 topic (LiDAR)"},
    {"--color-topic", "color_topic", &io::BagOptions::color_topic,
     "Bag: colour sensor_msgs/Image topic, bgr8/rgb8 (RGBD)"},
    {"--depth-topic", "depth_topic", &io::BagOptions::depth_topic,
     "Bag: depth sensor_msgs/Image topic, 16UC1 mm or 32FC1 m (RGBD)"},
    {"--camera-info-topic", "camera_info_topic", &io::BagOptions::camera_info_topic,
     "Bag: sensor_msgs/CameraInfo topic (RGBD)"},
    {"--odom-topic", "odom_topic", &io::BagOptions::odom_topic,
     "Bag: nav_msgs/Odometry topic (empty: the /tf chain odom frame -> body frame)"},
    {"--odom-frame", "odom_frame", &io::BagOptions::odom_frame, "Bag: odometry frame of the /tf chain"},
    {"--body-frame", "body_frame", &io::BagOptions::body_frame,
     "Bag: body frame (default: the Odometry child_frame_id, or base_link; another frame is reached through /tf)"},
};
}  // namespace

void addBagOptions(CLI::App& app, BagCli& cli) {
  for (const Field& f : kFields) cli.set.push_back(app.add_option(f.flag, cli.options.*f.member, f.help));
  cli.set.push_back(app.add_flag("--deskew", cli.options.deskew, "Bag: motion-compensate sweeps from per-point times"));
  app.add_flag("--list", cli.list, "Print the bag's topics, types, message counts and rates, then exit");
  cli.gap = app.add_option("--max-odom-gap", cli.max_odometry_gap_s,
                           "Frames between odometry samples further apart than this (seconds) are dropped")
                ->capture_default_str();
}

void readBagConfig(const ConfigNode& sd, BagCli& cli) {
  if (!cli.gap->count()) cli.max_odometry_gap_s = sd.get<double>("max_odom_gap", cli.max_odometry_gap_s);
  if (!sd.has("bag")) return;
  const ConfigNode b = sd.child("bag");
  std::size_t i = 0;
  for (const Field& f : kFields) {
    if (!cli.set[i++]->count()) cli.options.*f.member = b.get<std::string>(f.key, cli.options.*f.member);
  }
  if (!cli.set[i]->count()) cli.options.deskew = b.get<bool>("deskew", cli.options.deskew);
  for (const Field& f : kFields) b.known({f.key});  // read above unless the command line set them
  b.known({"deskew"});
  cli.options.max_color_depth_dt = b.get<double>("max_color_depth_dt", cli.options.max_color_depth_dt);
  if (b.has("T_body_sensor")) {
    const std::vector<double> v = b.getList<double>("T_body_sensor", 7);
    cli.options.T_body_sensor =
        poseFromPositionQuaternion({v[0], v[1], v[2]}, Eigen::Quaterniond(v[6], v[3], v[4], v[5]));
  }
}

int listBag(const std::string& bag) {
  const std::vector<io::BagTopicInfo> topics = io::listBagTopics(bag);
  std::printf("%-40s %-32s %10s %10s\n", "topic", "type", "messages", "rate_hz");
  for (const io::BagTopicInfo& t : topics)
    std::printf("%-40s %-32s %10zu %10.2f\n", t.topic.c_str(), t.type.c_str(), t.messages, t.rateHz());
  return 0;
}

}  // namespace slide
