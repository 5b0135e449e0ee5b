#include "frame_messages.h"

#include <cstring>
#include <stdexcept>

#include "msg/convert.h"

namespace slide {

namespace {
std::vector<uint8_t> bytesOf(const cv::Mat& m) {
  const cv::Mat c = m.isContinuous() ? m : m.clone();
  const auto* p = c.ptr<uint8_t>();
  return std::vector<uint8_t>(p, p + c.total() * c.elemSize());  // x86: uint16 already little-endian
}
}  // namespace

header_t frameHeader(int64_t utime, int robot, int seq) {
  header_t h;
  h.utime = utime;
  h.robot = robot;
  h.seq = seq;
  return h;
}

rgbd_frame_t toRgbdMessage(const cv::Mat& color, const cv::Mat& depth, const io::InstanceMask* mask,
                           const std::vector<float>* confidence, const io::CameraCalib& calib, int64_t utime, int robot,
                           int seq) {
  if (color.size() != depth.size()) throw std::invalid_argument("colour and depth images differ in size");
  rgbd_frame_t m;
  m.header = frameHeader(utime, robot, seq);
  m.intrinsics.width = depth.cols;
  m.intrinsics.height = depth.rows;
  m.intrinsics.fx = calib.fx;
  m.intrinsics.fy = calib.fy;
  m.intrinsics.cx = calib.cx;
  m.intrinsics.cy = calib.cy;
  m.intrinsics.depth_scale = calib.depth_scale;
  m.color = bytesOf(color);
  m.color_size = static_cast<int32_t>(m.color.size());
  m.depth = bytesOf(depth);
  m.depth_size = static_cast<int32_t>(m.depth.size());
  if (mask) {
    m.instance_mask = bytesOf(mask->mask);
    m.instance_class.assign(mask->class_id.begin(), mask->class_id.end());
    if (confidence && confidence->size() != mask->class_id.size())
      throw std::invalid_argument("one confidence per instance expected");
    if (confidence) m.instance_confidence = *confidence;
    else m.instance_confidence.assign(mask->class_id.size(), 1.0f);
  }
  m.mask_size = static_cast<int32_t>(m.instance_mask.size());
  m.num_instances = static_cast<int32_t>(m.instance_class.size());
  return m;
}

odometry_t toOdometryMessage(const Pose& pose, const Pose* prev, double dt, int64_t utime, int robot, int seq) {
  odometry_t m;
  m.header = frameHeader(utime, robot, seq);
  m.pose = msg::toLcm(pose);
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
  if (prev && dt > 0) {
    const Pose delta = prev->inverse() * pose;  // motion in the previous body frame
    const Vector6d xi = logSE3(delta);
    v = xi.head<3>() / dt;
    w = xi.tail<3>() / dt;
  }
  for (int i = 0; i < 3; ++i) {
    m.linear_velocity[i] = static_cast<float>(v[i]);
    m.angular_velocity[i] = static_cast<float>(w[i]);
  }
  return m;
}

}  // namespace slide
