#include "team/codec.h"

#include <cmath>
#include <variant>

namespace slide::team {
namespace {

constexpr std::uint8_t kBundleFormat = 1;
constexpr std::uint8_t kMapFormat = 1;
constexpr std::size_t kMaxObjects = 100000;

// Flags of a bundle header.
constexpr std::uint8_t kFirst = 1, kHasSigma = 2, kRelativeFromOdom = 4;
// Relative odometry is left out when the float32 poses reproduce it this closely (metres,
// rotation-matrix norm): far below odometry noise; float32 itself resolves 0.06 mm at 1 km.
constexpr double kDerivedTranslationTol = 1e-4, kDerivedRotationTol = 1e-5;
// Object tag bits: shape in bits 0-1, then defaults that were left out.
constexpr std::uint8_t kShapeMask = 3, kUnitConfidence = 4, kOneObservation = 8, kUprightAxis = 16;
// Rotation tag: index of the dropped (largest) quaternion component in bits 0-1; bit 2: yaw only.
constexpr std::uint8_t kYawOnly = 4;

bool finite(float v) { return std::isfinite(v); }

void writeRotation(ByteWriter& w, const Eigen::Quaterniond& qd) {
  Eigen::Vector4f q(static_cast<float>(qd.w()), static_cast<float>(qd.x()), static_cast<float>(qd.y()),
                    static_cast<float>(qd.z()));
  if (q[1] == 0.0f && q[2] == 0.0f) {  // rotation about z only: (w, z) with w >= 0
    if (q[0] < 0) q = -q;
    w.u8(kYawOnly);
    w.f32(q[0]);
    w.f32(q[3]);
    return;
  }
  int big = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(q[i]) > std::abs(q[big])) big = i;
  if (q[big] < 0) q = -q;
  w.u8(static_cast<std::uint8_t>(big));
  for (int i = 0; i < 4; ++i)
    if (i != big) w.f32(q[i]);
}

bool readRotation(ByteReader& r, Eigen::Quaterniond* out) {
  const std::uint8_t tag = r.u8();
  if (tag & ~std::uint8_t(7)) {
    r.fail("rotation tag " + std::to_string(tag) + " has unknown bits");
    return false;
  }
  double c[4] = {0, 0, 0, 0};
  if (tag & kYawOnly) {
    c[0] = r.f32();
    c[3] = r.f32();
  } else {
    const int big = tag & 3;
    double sq = 0;
    for (int i = 0; i < 4; ++i) {
      if (i == big) continue;
      const float v = r.f32();
      if (!finite(v)) {
        r.fail("non-finite quaternion component");
        return false;
      }
      c[i] = v;
      sq += c[i] * c[i];
    }
    if (sq > 1.0 + 1e-4) {
      r.fail("quaternion components exceed unit norm");
      return false;
    }
    c[big] = std::sqrt(std::max(0.0, 1.0 - sq));
  }
  Eigen::Quaterniond q(c[0], c[1], c[2], c[3]);
  if (!r.ok() || !std::isfinite(q.norm()) || q.norm() < 0.5) {
    r.fail("invalid rotation");
    return false;
  }
  *out = q.normalized();
  return true;
}

void writeVec3(ByteWriter& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.f32(static_cast<float>(v[i]));
}

Eigen::Vector3d readVec3(ByteReader& r) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const float f = r.f32();
    if (!finite(f)) r.fail("non-finite coordinate");
    v[i] = f;
  }
  return v;
}

float readScalar(ByteReader& r, const char* what) {
  const float f = r.f32();
  if (!finite(f)) r.fail(std::string("non-finite ") + what);
  return f;
}

void writePose(ByteWriter& w, const Pose& T) {
  writeRotation(w, Eigen::Quaterniond(T.rotation()));
  writeVec3(w, T.translation());
}

Pose readPose(ByteReader& r) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  readRotation(r, &q);
  const Eigen::Vector3d t = readVec3(r);
  Pose T = Pose::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = t;
  return T;
}

// A unit axis by its two smallest components; the tag holds the index and sign of the largest.
void writeAxis(ByteWriter& w, const Eigen::Vector3d& axis) {
  const Eigen::Vector3f a = axis.normalized().cast<float>();
  int big = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(a[i]) > std::abs(a[big])) big = i;
  w.u8(static_cast<std::uint8_t>(big | (a[big] < 0 ? 4 : 0)));
  for (int i = 0; i < 3; ++i)
    if (i != big) w.f32(a[i]);
}

Eigen::Vector3d readAxis(ByteReader& r) {
  const std::uint8_t tag = r.u8();
  const int big = tag & 3;
  if (big > 2 || (tag & ~std::uint8_t(7))) {
    r.fail("axis tag " + std::to_string(tag) + " invalid");
    return Eigen::Vector3d::UnitZ();
  }
  Eigen::Vector3d a;
  double sq = 0;
  for (int i = 0; i < 3; ++i) {
    if (i == big) continue;
    a[i] = readScalar(r, "axis component");
    sq += a[i] * a[i];
  }
  if (sq > 1.0 + 1e-4) r.fail("axis components exceed unit norm");
  a[big] = std::sqrt(std::max(0.0, 1.0 - sq)) * ((tag & 4) ? -1 : 1);
  return a.normalized();
}

// `for_place_recognition`: only what place recognition uses (class, id, position, size,
// yaw): confidence, observation counts, cylinder tilt and cuboid roll/pitch are left out.
void writeObjects(ByteWriter& w, const std::vector<Object>& objects, bool for_place_recognition = false) {
  w.varint(objects.size());
  std::int64_t prev_id = 0;
  for (const Object& original : objects) {
    Object o = original;
    if (for_place_recognition) {
      o.confidence = 1.0;
      o.num_observations = 1;
      if (auto* c = std::get_if<Cylinder>(&o.model)) c->axis = Eigen::Vector3d::UnitZ();
      if (auto* b = std::get_if<Cuboid>(&o.model)) {
        const Eigen::Vector3d t = b->pose.translation();
        b->pose = poseFromXyzYaw(t.x(), t.y(), t.z(), yawOf(b->pose.linear()));
      }
    }
    std::uint8_t tag = static_cast<std::uint8_t>(o.model.index());
    const float conf = static_cast<float>(o.confidence);
    if (conf == 1.0f) tag |= kUnitConfidence;
    if (o.num_observations == 1) tag |= kOneObservation;
    if (const auto* c = std::get_if<Cylinder>(&o.model)) {
      if (c->axis == Eigen::Vector3d::UnitZ()) tag |= kUprightAxis;
    }
    w.u8(tag);
    w.svarint(o.id - prev_id);
    prev_id = o.id;
    w.varint(static_cast<std::uint16_t>(o.class_id));  // int16 on the robot bus
    if (!(tag & kUnitConfidence)) w.f32(conf);
    if (!(tag & kOneObservation)) w.svarint(o.num_observations);
    if (const auto* b = std::get_if<Cuboid>(&o.model)) {
      writePose(w, b->pose);
      writeVec3(w, b->dims);
    } else if (const auto* c = std::get_if<Cylinder>(&o.model)) {
      writeVec3(w, c->root);
      if (!(tag & kUprightAxis)) writeAxis(w, c->axis);
      w.f32(static_cast<float>(c->radius));
      w.f32(static_cast<float>(c->length));
    } else {
      const auto& e = std::get<Ellipsoid>(o.model);
      writeVec3(w, e.centroid);
      w.f32(static_cast<float>(e.radius));
      w.f32(static_cast<float>(e.height));
    }
  }
}

bool readObjects(ByteReader& r, std::vector<Object>* out) {
  const std::uint64_t n = r.varint();
  // Every object takes at least 3 bytes: a bound that rejects absurd counts before allocating.
  if (n > kMaxObjects || n * 3 > r.remaining()) {
    r.fail("object count " + std::to_string(n) + " exceeds what the message can hold");
    return false;
  }
  out->clear();
  out->reserve(n);
  std::int64_t prev_id = 0;
  for (std::uint64_t i = 0; i < n && r.ok(); ++i) {
    Object o;
    const std::uint8_t tag = r.u8();
    const int shape = tag & kShapeMask;
    if (shape > 2 || (tag & ~std::uint8_t(31))) {
      r.fail("object " + std::to_string(i) + ": tag " + std::to_string(tag) + " invalid");
      return false;
    }
    o.id = prev_id + r.svarint();
    prev_id = o.id;
    const std::uint64_t cls = r.varint();
    if (cls > 0xffff) r.fail("object " + std::to_string(i) + ": class id out of int16 range");
    o.class_id = static_cast<std::int16_t>(static_cast<std::uint16_t>(cls));
    o.confidence = (tag & kUnitConfidence) ? 1.0 : readScalar(r, "confidence");
    if (tag & kOneObservation) {
      o.num_observations = 1;
    } else {
      const std::int64_t nobs = r.svarint();
      if (nobs < INT32_MIN || nobs > INT32_MAX) r.fail("num_observations out of range");
      o.num_observations = static_cast<int>(nobs);
    }
    if (shape == 0) {
      Cuboid b;
      b.pose = readPose(r);
      b.dims = readVec3(r);
      o.model = b;
    } else if (shape == 1) {
      Cylinder c;
      c.root = readVec3(r);
      c.axis = (tag & kUprightAxis) ? Eigen::Vector3d::UnitZ() : readAxis(r);
      c.radius = readScalar(r, "radius");
      c.length = readScalar(r, "length");
      o.model = c;
    } else {
      if (tag & kUprightAxis) r.fail("object " + std::to_string(i) + ": upright flag on an ellipsoid");
      Ellipsoid e;
      e.centroid = readVec3(r);
      e.radius = readScalar(r, "radius");
      e.height = readScalar(r, "height");
      o.model = e;
    }
    if (shape == 0 && (tag & kUprightAxis)) r.fail("object " + std::to_string(i) + ": upright flag on a cuboid");
    out->push_back(std::move(o));
  }
  return r.ok();
}

template <typename T>
std::optional<T> finish(ByteReader& r, T value, std::string* error) {
  if (r.ok() && r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " trailing bytes");
  if (!r.ok()) {
    if (error) *error = r.error();
    return std::nullopt;
  }
  return value;
}

}  // namespace

Bytes encodeBundle(const Bundle& b, const Pose* previous_odom) {
  ByteWriter w;
  w.u8(kBundleFormat);
  bool has_sigma = false;
  for (float s : b.odom_sigma) has_sigma |= s != 0.0f;
  bool derived = false;
  if (!b.first && previous_odom) {
    // What receivers would compute from the two float32 poses, against the true relative motion.
    ByteWriter pw;
    writePose(pw, b.odom_pose);
    ByteReader pr(pw.data());
    const Pose rel = previous_odom->inverse() * readPose(pr);
    derived = (rel.translation() - b.relative_odom.translation()).norm() <= kDerivedTranslationTol &&
              (rel.linear() - b.relative_odom.linear()).norm() <= kDerivedRotationTol;
  }
  w.u8(static_cast<std::uint8_t>((b.first ? kFirst : 0) | (has_sigma ? kHasSigma : 0) |
                                 (derived ? kRelativeFromOdom : 0)));
  w.svarint(b.utime);
  writePose(w, b.odom_pose);
  if (!derived) writePose(w, b.relative_odom);
  if (has_sigma)
    for (float s : b.odom_sigma) w.f32(s);
  writeObjects(w, b.objects);
  return w.take();
}

std::optional<Bundle> decodeBundle(const Bytes& data, std::int32_t origin, std::int32_t seq, std::string* error,
                                   const Pose* previous_odom, bool* needs_previous) {
  ByteReader r(data);
  Bundle b;
  b.origin = origin;
  b.seq = seq;
  const std::uint8_t format = r.u8();
  if (r.ok() && format != kBundleFormat) r.fail("unknown bundle format " + std::to_string(format));
  const std::uint8_t flags = r.u8();
  if (r.ok() && (flags & ~std::uint8_t(kFirst | kHasSigma | kRelativeFromOdom)))
    r.fail("unknown bundle flags " + std::to_string(flags));
  if (r.ok() && (flags & kFirst) && (flags & kRelativeFromOdom)) r.fail("first bundle cannot refer to a previous one");
  b.first = flags & kFirst;
  b.utime = r.svarint();
  b.odom_pose = readPose(r);
  const bool derived = flags & kRelativeFromOdom;
  if (!derived) b.relative_odom = readPose(r);
  else if (previous_odom) b.relative_odom = previous_odom->inverse() * b.odom_pose;
  if (needs_previous) *needs_previous = derived && !previous_odom;
  if (flags & kHasSigma)
    for (float& s : b.odom_sigma) s = readScalar(r, "odom sigma");
  readObjects(r, &b.objects);
  return finish(r, std::move(b), error);
}

Bytes encodeMap(const SharedMap& m) {
  ByteWriter w;
  w.u8(kMapFormat);
  w.svarint(m.utime);
  w.svarint(m.frame_robot);
  writeObjects(w, m.objects, true);
  return w.take();
}

std::optional<SharedMap> decodeMap(const Bytes& data, std::int32_t robot, std::int32_t version, std::string* error) {
  ByteReader r(data);
  SharedMap m;
  m.robot = robot;
  m.version = version;
  const std::uint8_t format = r.u8();
  if (r.ok() && format != kMapFormat) r.fail("unknown map format " + std::to_string(format));
  m.utime = r.svarint();
  const std::int64_t frame = r.svarint();
  if (frame < INT32_MIN || frame > INT32_MAX) r.fail("frame robot out of range");
  m.frame_robot = static_cast<std::int32_t>(frame);
  readObjects(r, &m.objects);
  return finish(r, std::move(m), error);
}

}  // namespace slide::team
