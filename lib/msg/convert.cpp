#include "msg/convert.h"

#include <cmath>
#include <stdexcept>

namespace slide::msg {

namespace {
template <typename T>
Eigen::Vector3d vec(const T* v) {
  return {v[0], v[1], v[2]};
}
template <typename T>
void put(const Eigen::Vector3d& v, T* out) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<T>(v[i]);
}
}  // namespace

pose3_t toLcm(const Pose& T) {
  pose3_t m;
  put(T.translation(), m.position);
  const Eigen::Quaterniond q(T.linear());
  m.orientation[0] = q.w();
  m.orientation[1] = q.x();
  m.orientation[2] = q.y();
  m.orientation[3] = q.z();
  return m;
}

Pose fromLcm(const pose3_t& m) {
  return poseFromPositionQuaternion(vec(m.position),
                                    Eigen::Quaterniond(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]));
}

bool usablePose(const pose3_t& m) {
  double qn = 0;
  for (double v : m.position)
    if (!std::isfinite(v)) return false;
  for (double v : m.orientation) {
    if (!std::isfinite(v)) return false;
    qn += v * v;
  }
  return qn > 0.25;
}

object_t toLcm(const Object& o) {
  object_t m;
  m.id = o.id;
  m.class_id = static_cast<int16_t>(o.class_id);
  m.confidence = static_cast<float>(o.confidence);
  m.num_observations = o.num_observations;
  m.num_cuboid = m.num_cylinder = m.num_ellipsoid = 0;
  if (const auto* c = std::get_if<Cuboid>(&o.model)) {
    cuboid_t cm;
    cm.pose = toLcm(c->pose);
    put(c->dims, cm.dims);
    m.cuboid.push_back(cm);
    if (o.other_reading) {  // a second box: the other reading of a box whose length went unseen
      cm.pose = toLcm(o.other_reading->pose);
      put(o.other_reading->dims, cm.dims);
      m.cuboid.push_back(cm);
    }
    m.num_cuboid = static_cast<int8_t>(m.cuboid.size());
  } else if (const auto* c = std::get_if<Cylinder>(&o.model)) {
    cylinder_t cm;
    put(c->root, cm.root);
    put(c->axis, cm.axis);
    cm.radius = static_cast<float>(c->radius);
    cm.length = static_cast<float>(c->length);
    m.cylinder.push_back(cm);
    m.num_cylinder = 1;
  } else {
    const auto& e = std::get<Ellipsoid>(o.model);
    ellipsoid_t em;
    put(e.centroid, em.centroid);
    em.radius = static_cast<float>(e.radius);
    em.height = static_cast<float>(e.height);
    m.ellipsoid.push_back(em);
    m.num_ellipsoid = 1;
  }
  return m;
}

Object fromLcm(const object_t& m) {
  // One model; a cuboid may come with its other reading as a second box.
  const bool one = (m.num_cuboid >= 1 && m.num_cuboid <= 2 && m.num_cylinder == 0 && m.num_ellipsoid == 0) ||
                   (m.num_cuboid == 0 && m.num_cylinder + m.num_ellipsoid == 1 && m.num_cylinder >= 0 &&
                    m.num_ellipsoid >= 0);
  if (!one)
    throw std::invalid_argument("object_t id " + std::to_string(m.id) + ": expected one cuboid (or two: its two "
                                "readings), one cylinder or one ellipsoid, got " + std::to_string(m.num_cuboid) + "/" +
                                std::to_string(m.num_cylinder) + "/" + std::to_string(m.num_ellipsoid));
  Object o;
  o.id = m.id;
  o.class_id = m.class_id;
  o.confidence = m.confidence;
  o.num_observations = m.num_observations;
  if (m.num_cuboid) {
    o.model = Cuboid{fromLcm(m.cuboid[0].pose), vec(m.cuboid[0].dims)};
    if (m.num_cuboid == 2) o.other_reading = Cuboid{fromLcm(m.cuboid[1].pose), vec(m.cuboid[1].dims)};
  } else if (m.num_cylinder) {
    const cylinder_t& c = m.cylinder[0];
    o.model = Cylinder{vec(c.root), vec(c.axis).normalized(), c.radius, c.length};
  } else {
    const ellipsoid_t& e = m.ellipsoid[0];
    o.model = Ellipsoid{vec(e.centroid), e.radius, e.height};
  }
  return o;
}

keypose_bundle_t toLcm(const KeyPoseBundle& b) {
  keypose_bundle_t m;
  m.header.utime = b.utime;
  m.header.robot = b.robot;
  m.header.seq = b.seq;
  m.odom_pose = toLcm(b.odom_pose);
  m.relative_odom = toLcm(b.relative_odom);
  for (int i = 0; i < 6; ++i) m.odom_sigma[i] = static_cast<float>(b.odom_sigma[i]);
  for (const Object& o : b.objects) m.objects.push_back(toLcm(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

KeyPoseBundle fromLcm(const keypose_bundle_t& m, std::vector<std::string>* dropped) {
  KeyPoseBundle b;
  b.robot = m.header.robot;
  b.seq = m.header.seq;
  b.utime = m.header.utime;
  b.odom_pose = fromLcm(m.odom_pose);
  b.relative_odom = fromLcm(m.relative_odom);
  for (int i = 0; i < 6; ++i) b.odom_sigma[i] = m.odom_sigma[i];
  for (const object_t& o : m.objects) {
    try {
      b.objects.push_back(fromLcm(o));
    } catch (const std::invalid_argument& e) {
      if (dropped) dropped->push_back(e.what());
    }
  }
  return b;
}

}  // namespace slide::msg
