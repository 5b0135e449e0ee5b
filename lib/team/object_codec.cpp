#include "team/object_codec.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "team/quantise.h"

namespace slide::team {
namespace {

constexpr std::size_t kMaxObjects = 100000;
constexpr std::size_t kMinObjectBytes = 6;  // tag, id, three positions, one size byte

// Tag bits.
constexpr std::uint8_t kShapeMask = 3;
constexpr std::uint8_t kSameClass = 4;        // class as the previous object's
constexpr std::uint8_t kOriented = 8;         // bundle: cylinder axis tilted / cuboid roll, pitch
constexpr std::uint8_t kPositionFloat = 16;   // position as float32 (out of range)
constexpr std::uint8_t kSizeFloat = 32;       // sizes as float32 (out of range)
constexpr std::uint8_t kConfidenceFloat = 64; // bundle: confidence as float32 (outside 0..1)
constexpr std::uint8_t kAxisDown = 128;       // bundle, tilted cylinder: axis z < 0
constexpr std::uint8_t kOtherReading = 128;   // bundle, cuboid: its other reading follows
constexpr std::uint8_t kMapBits = kShapeMask | kSameClass | kPositionFloat | kSizeFloat;

constexpr double kPositionUnit = 0.01;     // bundles (body frame)
constexpr double kMapPositionUnit = 0.05;  // maps: place recognition works at decimetres
constexpr std::int64_t kBodyPositionLimit = 32767;        // +-327 m
constexpr std::int64_t kMapPositionLimit = 1LL << 31;     // +-107000 km
constexpr double kTiltUnit = 1e-3;                        // axis components, roll, pitch
constexpr std::int64_t kRollPitchLimit = 3142;            // pi
constexpr double kConfidenceUnit = 1.0 / 255;
constexpr double kOtherOffsetUnit = 0.05;  // a box's other centre from its own: 1 byte within 3.15 m ...
constexpr std::int64_t kOtherOffsetLimit = 2000;  // ... and at most 100 m
// Size units per shape: cylinder radius, length; cuboid dims; ellipsoid radius, height.
constexpr double kCylinderUnits[2] = {0.01, 0.1};
constexpr double kCuboidUnit = 0.05;
constexpr double kEllipsoidUnits[2] = {0.01, 0.05};

bool within(std::int64_t v, std::int64_t limit) { return v >= -limit && v <= limit; }

// The other reading of a box is the same box turned a quarter about its own vertical: only its
// centre and extents travel (the centre as a difference from the box's).
bool quarterTurnOf(const Cuboid& box, const Cuboid& other) {
  const Eigen::Matrix3d m = box.pose.linear().transpose() * other.pose.linear();
  return std::abs(m(2, 2) - 1.0) < 1e-6 && std::abs(std::abs(std::atan2(m(1, 0), m(0, 0))) - M_PI / 2) < 1e-3;
}

std::string at(std::uint64_t i, const char* what) { return "object " + std::to_string(i) + ": " + what; }

Eigen::Vector3d positionOf(const Object& o) {
  if (const auto* b = std::get_if<Cuboid>(&o.model)) return b->pose.translation();
  if (const auto* c = std::get_if<Cylinder>(&o.model)) return c->root;
  return std::get<Ellipsoid>(o.model).centroid;
}

std::vector<double> sizesOf(const Object& o) {
  if (const auto* b = std::get_if<Cuboid>(&o.model)) return {b->dims.x(), b->dims.y(), b->dims.z()};
  if (const auto* c = std::get_if<Cylinder>(&o.model)) return {c->radius, c->length};
  const auto& e = std::get<Ellipsoid>(o.model);
  return {e.radius, e.height};
}

double sizeUnit(int shape, std::size_t i) {
  if (shape == 0) return kCuboidUnit;
  return shape == 1 ? kCylinderUnits[i] : kEllipsoidUnits[i];
}

// The optional quantised form of a group of values (all or none).
template <typename F>
std::optional<std::vector<std::int64_t>> quantiseAll(const std::vector<double>& v, F q) {
  std::vector<std::int64_t> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto x = q(v[i], i);
    if (!x) return std::nullopt;
    out.push_back(*x);
  }
  return out;
}

float readFinite(ByteReader& r, std::uint64_t i, const char* what) {
  const float f = r.f32();
  if (r.ok() && !std::isfinite(f)) r.fail(at(i, what) + " is not finite");
  return f;
}

}  // namespace

void writeObjects(ByteWriter& w, const std::vector<Object>& objects, ObjectListKind kind) {
  const bool body = kind != ObjectListKind::Map, counts = kind == ObjectListKind::Bundle;
  const double unit = body ? kPositionUnit : kMapPositionUnit;
  w.varint(objects.size());
  std::int64_t prev_id = 0;
  int prev_class = -1;
  Eigen::Matrix<std::int64_t, 3, 1> prev_q = Eigen::Matrix<std::int64_t, 3, 1>::Zero();
  for (const Object& o : objects) {
    const int shape = static_cast<int>(o.model.index());
    std::uint8_t tag = static_cast<std::uint8_t>(shape);
    const int cls = static_cast<std::uint16_t>(o.class_id);  // int16 on the robot bus
    if (cls == prev_class) tag |= kSameClass;
    prev_class = cls;
    // Position.
    const Eigen::Vector3d p = positionOf(o);
    const std::int64_t limit = body ? kBodyPositionLimit : kMapPositionLimit;
    const auto qp = quantiseAll({p.x(), p.y(), p.z()}, [&](double v, std::size_t) { return quantise(v, unit, limit); });
    if (!qp) tag |= kPositionFloat;
    // The other reading of a box whose length went unseen (bundles only): its centre as an offset
    // from the box's as the receiver decodes it (so it is as exact), in kOtherOffsetUnit when the
    // position is quantised.
    const Cuboid* other = nullptr;
    Eigen::Vector3d other_offset = Eigen::Vector3d::Zero();
    std::optional<std::vector<std::int64_t>> q_offset;
    if (const auto* b = std::get_if<Cuboid>(&o.model);
        body && b && o.other_reading && quarterTurnOf(*b, *o.other_reading) && o.other_reading->dims.allFinite()) {
      const Eigen::Vector3d sent = qp ? Eigen::Vector3d((*qp)[0] * unit, (*qp)[1] * unit, (*qp)[2] * unit) : p;
      other_offset = o.other_reading->pose.translation() - sent;
      q_offset = quantiseAll({other_offset.x(), other_offset.y(), other_offset.z()},
                             [&](double v, std::size_t) { return quantise(v, kOtherOffsetUnit, kOtherOffsetLimit); });
      if (qp ? q_offset.has_value() : other_offset.allFinite()) other = &*o.other_reading;
    }
    // Sizes (the other reading's after the object's own).
    auto sizes = sizesOf(o);
    if (other) sizes.insert(sizes.end(), {other->dims.x(), other->dims.y(), other->dims.z()});
    const auto qs = quantiseAll(sizes, [&](double v, std::size_t i) -> std::optional<std::int64_t> {
      const auto q = quantiseU8(v, sizeUnit(shape, i % 3));
      return q ? std::optional<std::int64_t>(*q) : std::nullopt;
    });
    if (!qs) tag |= kSizeFloat;
    // Orientation details (bundles only).
    const std::optional<std::uint8_t> qconf =
        o.confidence >= 0 && o.confidence <= 1 ? quantiseU8(o.confidence, kConfidenceUnit) : std::nullopt;
    std::int64_t tilt[2] = {0, 0};
    if (body) {
      if (!qconf) tag |= kConfidenceFloat;
      if (const auto* c = std::get_if<Cylinder>(&o.model)) {
        const Eigen::Vector3d a = c->axis.normalized();
        // (A degenerate, non-finite axis goes as upright.)
        tilt[0] = quantise(a.x(), kTiltUnit, 1000).value_or(0);
        tilt[1] = quantise(a.y(), kTiltUnit, 1000).value_or(0);
        if (tilt[0] != 0 || tilt[1] != 0 || a.z() < 0) tag |= kOriented;
        if (a.z() < 0) tag |= kAxisDown;
      } else if (const auto* b = std::get_if<Cuboid>(&o.model)) {
        const Eigen::Vector3d rpy = rpyOf(b->pose.linear());
        tilt[0] = quantise(rpy[0], kTiltUnit, kRollPitchLimit).value_or(0);  // (non-finite: level)
        tilt[1] = quantise(rpy[1], kTiltUnit, kRollPitchLimit).value_or(0);
        if (tilt[0] != 0 || tilt[1] != 0) tag |= kOriented;
        if (other) tag |= kOtherReading;
      }
    }
    w.u8(tag);
    w.svarint(wrappingSub(o.id, prev_id));
    prev_id = o.id;
    if (!(tag & kSameClass)) w.varint(static_cast<std::uint64_t>(cls));
    if (body) {
      if (!(tag & kConfidenceFloat)) w.u8(qconf.value_or(0));
      else w.f32(static_cast<float>(o.confidence));
    }
    if (counts) w.svarint(o.num_observations);
    if (qp) {
      for (int i = 0; i < 3; ++i) w.svarint(body ? (*qp)[i] : (*qp)[i] - prev_q[i]);
      if (!body) prev_q = Eigen::Matrix<std::int64_t, 3, 1>((*qp)[0], (*qp)[1], (*qp)[2]);
    } else {
      for (int i = 0; i < 3; ++i) w.f32(static_cast<float>(p[i]));
    }
    if (const auto* b = std::get_if<Cuboid>(&o.model)) {
      const double yaw = rpyOf(b->pose.linear())[2];
      if (body) w.u16(quantiseTurn16(yaw));
      else w.u8(quantiseTurn8(yaw));
      if (tag & kOriented) w.svarint(tilt[0]), w.svarint(tilt[1]);
    } else if (tag & kOriented) {
      w.svarint(tilt[0]);
      w.svarint(tilt[1]);
    }
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      if (qs) w.u8(static_cast<std::uint8_t>((*qs)[i]));
      else w.f32(static_cast<float>(sizes[i]));
    }
    if (other)
      for (int i = 0; i < 3; ++i) {
        if (qp) w.svarint((*q_offset)[i]);
        else w.f32(static_cast<float>(other_offset[i]));
      }
  }
}

bool readObjects(ByteReader& r, std::vector<Object>* out, ObjectListKind kind) {
  const bool body = kind != ObjectListKind::Map, counts = kind == ObjectListKind::Bundle;
  const double unit = body ? kPositionUnit : kMapPositionUnit;
  const std::uint64_t n = r.varint();
  if (!r.ok()) return false;
  if (n > kMaxObjects || n * kMinObjectBytes > r.remaining()) {
    r.fail("object count " + std::to_string(n) + " exceeds what the message can hold");
    return false;
  }
  out->clear();
  out->reserve(n);
  std::int64_t prev_id = 0;
  int prev_class = -1;
  Eigen::Matrix<std::int64_t, 3, 1> prev_q = Eigen::Matrix<std::int64_t, 3, 1>::Zero();
  for (std::uint64_t i = 0; i < n && r.ok(); ++i) {
    Object o;
    const std::uint8_t tag = r.u8();
    const int shape = tag & kShapeMask;
    if (!r.ok()) return false;
    if (shape > 2) return r.fail(at(i, "shape ") + std::to_string(shape) + " unknown"), false;
    if (!body && (tag & ~kMapBits)) return r.fail(at(i, "map object tag ") + std::to_string(tag) + " has unknown bits"), false;
    if ((tag & kAxisDown) && shape == 1 && !(tag & kOriented))
      return r.fail(at(i, "axis-down flag on an object without a tilted axis")), false;
    if ((tag & kAxisDown) && shape == 2) return r.fail(at(i, "axis-down flag on an ellipsoid")), false;
    const bool has_other = shape == 0 && (tag & kOtherReading);
    if (shape == 2 && (tag & kOriented)) return r.fail(at(i, "orientation flag on an ellipsoid")), false;
    o.id = wrappingAdd(prev_id, r.svarint());
    prev_id = o.id;
    if (tag & kSameClass) {
      if (prev_class < 0) return r.fail(at(i, "same-class flag on the first object")), false;
    } else {
      const std::uint64_t cls = r.varint();
      if (r.ok() && cls > 0xffff) return r.fail(at(i, "class id out of int16 range")), false;
      prev_class = static_cast<int>(cls);
    }
    o.class_id = static_cast<std::int16_t>(static_cast<std::uint16_t>(prev_class));
    if (!body && (tag & kConfidenceFloat)) return r.fail(at(i, "confidence flag in a map")), false;
    if (body) o.confidence = (tag & kConfidenceFloat) ? readFinite(r, i, "confidence") : r.u8() * kConfidenceUnit;
    if (counts) {
      const std::int64_t nobs = r.svarint();
      if (r.ok() && (nobs < INT32_MIN || nobs > INT32_MAX)) return r.fail(at(i, "num_observations out of range")), false;
      o.num_observations = static_cast<int>(nobs);
    }
    Eigen::Vector3d p;
    if (tag & kPositionFloat) {
      for (int k = 0; k < 3; ++k) p[k] = readFinite(r, i, "position");
    } else {
      const std::int64_t limit = body ? kBodyPositionLimit : kMapPositionLimit;
      for (int k = 0; k < 3; ++k) {
        const std::int64_t v = r.svarint();
        if (r.ok() && !within(v, body ? limit : 2 * limit)) return r.fail(at(i, "position out of range")), false;
        const std::int64_t q = v + (body ? 0 : prev_q[k]);
        if (r.ok() && !within(q, limit)) return r.fail(at(i, "position out of range")), false;
        if (!body) prev_q[k] = q;
        p[k] = static_cast<double>(q) * unit;
      }
    }
    double tilt[2] = {0, 0};
    double yaw = 0;
    if (shape == 0) yaw = body ? turn16ToAngle(r.u16()) : turn8ToAngle(r.u8());
    if (tag & kOriented) {
      const std::int64_t limit = shape == 0 ? kRollPitchLimit : 1000;
      for (double& t : tilt) {
        const std::int64_t q = r.svarint();
        if (r.ok() && !within(q, limit)) return r.fail(at(i, "tilt out of range")), false;
        t = static_cast<double>(q) * kTiltUnit;
      }
      // (Rounding a horizontal axis may take the components a little beyond unit norm.)
      if (shape == 1 && tilt[0] * tilt[0] + tilt[1] * tilt[1] > 1.0 + 2e-3)
        return r.fail(at(i, "axis components exceed unit norm")), false;
    }
    double sizes[6] = {0, 0, 0, 0, 0, 0};
    const int num_sizes = (shape == 0 ? 3 : 2) * (has_other ? 2 : 1);
    for (int k = 0; k < num_sizes; ++k)
      sizes[k] = (tag & kSizeFloat) ? readFinite(r, i, "size") : r.u8() * sizeUnit(shape, static_cast<std::size_t>(k % 3));
    if (shape == 0) {
      Cuboid b;
      b.pose = poseFromXyzRpy(p, tilt[0], tilt[1], yaw);
      b.dims = {sizes[0], sizes[1], sizes[2]};
      o.model = b;
      if (has_other) {
        Eigen::Vector3d d;
        for (int k = 0; k < 3; ++k) {
          if (tag & kPositionFloat) {
            d[k] = readFinite(r, i, "other reading's position");
          } else {
            const std::int64_t q = r.svarint();
            if (r.ok() && !within(q, kOtherOffsetLimit)) return r.fail(at(i, "other reading's position out of range")), false;
            d[k] = static_cast<double>(q) * kOtherOffsetUnit;
          }
        }
        Cuboid other = b;
        other.pose.translation() = p + d;
        other.pose.linear() = b.pose.linear() * rotZ(M_PI / 2);
        other.dims = {sizes[3], sizes[4], sizes[5]};
        o.other_reading = other;
      }
    } else if (shape == 1) {
      Cylinder c;
      c.root = p;
      const double z = std::sqrt(std::max(0.0, 1.0 - tilt[0] * tilt[0] - tilt[1] * tilt[1]));
      c.axis = Eigen::Vector3d(tilt[0], tilt[1], (tag & kAxisDown) ? -z : z).normalized();
      c.radius = sizes[0];
      c.length = sizes[1];
      o.model = c;
    } else {
      o.model = Ellipsoid{p, sizes[0], sizes[1]};
    }
    out->push_back(std::move(o));
  }
  return r.ok();
}

}  // namespace slide::team
