#include "msg/frontend_convert.h"

#include <cmath>
#include <limits>

#include "msg/convert.h"

namespace slide::msg {

namespace {
constexpr float kFreeQuantum = 0.1f;  // metres per unit of object_instance_t::free_xy
}  // namespace

io::LabelledScan fromLcm(const lidar_scan_t& m, frontend::InputIssues& issues) {
  io::LabelledScan s;
  const std::size_t n = std::min<std::size_t>(m.xyz.size(), static_cast<std::size_t>(std::max(0, m.num_points)));
  s.xyz.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (m.xyz[i].size() == 3) s.xyz.emplace_back(m.xyz[i][0], m.xyz[i][1], m.xyz[i][2]);
    else s.xyz.emplace_back(Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  }
  s.intensity.assign(m.intensity.begin(), m.intensity.begin() + std::min(n, m.intensity.size()));
  if (m.has_labels) {
    if (m.num_labels != m.num_points || m.semantic.size() != n || m.instance.size() != n) {
      issues.count("label count mismatch");
    } else {
      s.semantic.reserve(n);
      s.instance.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        s.semantic.push_back(static_cast<uint16_t>(m.semantic[i]));
        s.instance.push_back(static_cast<uint16_t>(m.instance[i]));
      }
    }
  }
  return s;
}

lidar_scan_t toLcm(const io::LabelledScan& scan, const header_t& header) {
  lidar_scan_t m;
  m.header = header;
  m.num_points = static_cast<int32_t>(scan.size());
  m.xyz.resize(scan.size());
  m.intensity.resize(scan.size(), 0.0f);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    m.xyz[i] = {scan.xyz[i].x(), scan.xyz[i].y(), scan.xyz[i].z()};
    if (i < scan.intensity.size()) m.intensity[i] = scan.intensity[i];
  }
  m.has_labels = scan.hasLabels();
  m.num_labels = m.has_labels ? m.num_points : 0;
  if (m.has_labels) {
    m.semantic.assign(scan.semantic.begin(), scan.semantic.end());
    if (scan.instance.size() == scan.size()) m.instance.assign(scan.instance.begin(), scan.instance.end());
    else m.instance.assign(scan.size(), 0);
  }
  return m;
}

std::optional<frontend::RgbdFrame> fromLcm(const rgbd_frame_t& m, frontend::InputIssues& issues) {
  frontend::RgbdFrame f;
  const camera_intrinsics_t& k = m.intrinsics;
  f.intrinsics = {k.width, k.height, k.fx, k.fy, k.cx, k.cy, k.depth_scale};
  if (k.width <= 0 || k.height <= 0) {
    issues.count("invalid intrinsics");
    return std::nullopt;
  }
  const std::size_t pixels = static_cast<std::size_t>(k.width) * k.height;
  if (m.depth.size() != 2 * pixels) {
    issues.count(m.depth.empty() ? "missing depth image" : "image size does not match intrinsics");
    return std::nullopt;
  }
  if (!m.instance_mask.empty() && m.instance_mask.size() != 2 * pixels) {
    issues.count("image size does not match intrinsics");
    return std::nullopt;
  }
  if (!m.color.empty() && m.color.size() != 3 * pixels) issues.count("colour image size does not match intrinsics");
  else f.color = m.color;
  f.depth.resize(pixels);
  f.mask.assign(pixels, 0);
  for (std::size_t i = 0; i < pixels; ++i) {
    f.depth[i] = static_cast<uint16_t>(m.depth[2 * i] | (m.depth[2 * i + 1] << 8));
    if (!m.instance_mask.empty()) f.mask[i] = static_cast<uint16_t>(m.instance_mask[2 * i] | (m.instance_mask[2 * i + 1] << 8));
  }
  f.instance_class.assign(m.instance_class.begin(), m.instance_class.end());
  f.instance_confidence.assign(m.instance_confidence.begin(), m.instance_confidence.end());
  return f;
}

frame_instances_t toLcm(const frontend::FrameInstances& f, const header_t& header) {
  frame_instances_t m;
  m.header = header;
  m.odom_pose = toLcm(f.odom_pose);
  m.num_instances = static_cast<int32_t>(f.instances.size());
  for (const auto& inst : f.instances) {
    object_instance_t o;
    o.instance_id = inst.id;
    o.class_id = static_cast<int16_t>(inst.class_id);
    o.confidence = inst.confidence;
    o.num_points = static_cast<int32_t>(inst.points.size());
    o.xyz.assign(inst.points.size(), std::vector<float>(3, 0.0f));
    for (std::size_t i = 0; i < inst.points.size(); ++i)
      for (int k = 0; k < 3; ++k) o.xyz[i][k] = inst.points[i][k];
    o.free_z = inst.free_space.empty() ? 0.0f : inst.free_space.front().z();
    for (const auto& q : inst.free_space) {
      const float x = std::round(q.x() / kFreeQuantum), y = std::round(q.y() / kFreeQuantum);
      if (std::abs(x) <= 32767 && std::abs(y) <= 32767)
        o.free_xy.push_back({static_cast<int16_t>(x), static_cast<int16_t>(y)});
    }
    o.num_free = static_cast<int32_t>(o.free_xy.size());
    m.instances.push_back(std::move(o));
  }
  return m;
}

frontend::FrameInstances fromLcm(const frame_instances_t& m) {
  frontend::FrameInstances f;
  f.utime = m.header.utime;
  f.odom_pose = fromLcm(m.odom_pose);
  for (const auto& o : m.instances) {
    frontend::Instance inst;
    inst.id = o.instance_id;
    inst.class_id = o.class_id;
    inst.confidence = o.confidence;
    inst.points.reserve(o.xyz.size());
    for (const auto& p : o.xyz)
      if (p.size() == 3) inst.points.emplace_back(p[0], p[1], p[2]);
    if (std::isfinite(o.free_z)) {
      inst.free_space.reserve(o.free_xy.size());
      for (const auto& c : o.free_xy)
        if (c.size() == 2) inst.free_space.emplace_back(c[0] * kFreeQuantum, c[1] * kFreeQuantum, o.free_z);
    }
    f.instances.push_back(std::move(inst));
  }
  return f;
}

}  // namespace slide::msg
