#include "team/codec.h"

#include <cmath>

#include "team/object_codec.h"
#include "team/quantise.h"

namespace slide::team {
namespace {

constexpr std::uint8_t kBundleFormat = 3;  // 3: chained utime and step predicted from the previous ones
constexpr std::uint8_t kMapFormat = 3;  // 3: positions in 5 cm, cuboid yaw in 8 bits
constexpr std::uint8_t kMapDeltaFormat = 1;

// Flags of a bundle header.
constexpr std::uint8_t kFirst = 1;
constexpr std::uint8_t kHasSigma = 2;       // sigma written (else zero, or the previous one when chained)
constexpr std::uint8_t kChained = 4;        // utime, odometry pose and sigma relative to bundle seq-1
constexpr std::uint8_t kRelativeFloat = 8;  // relative odometry as float32 (too large to quantise)
constexpr std::uint8_t kSigmaFloat = 16;    // sigma written as float32 (out of the log-scale range)
constexpr std::uint8_t kTeam = 32;          // objects as the team bus carries them (ObjectListKind::TeamBundle)
constexpr std::uint8_t kGap = 64;           // a varint follows the flags: KeyPoseBundle::gap (>= 1)
constexpr std::uint8_t kAllFlags = kFirst | kHasSigma | kChained | kRelativeFloat | kSigmaFloat | kTeam | kGap;

constexpr double kMetre = 1e-3, kRadian = 1e-4;
constexpr std::int64_t kTranslationLimit = 1000000000;  // 1000 km
constexpr std::int64_t kRotationLimit = 31416;          // pi
// A chained bundle's relative odometry must agree this well with the two poses.
constexpr double kChainTranslationTol = 2e-3, kChainRotationTol = 2e-4;

using Quantised = std::array<std::int64_t, 6>;  // translation (mm), rotation vector (1e-4 rad)

std::optional<Quantised> quantiseStep(const Pose& T) {
  const Eigen::AngleAxisd aa(T.linear());
  const Eigen::Vector3d phi = aa.angle() * aa.axis();
  Quantised q;
  for (int i = 0; i < 3; ++i) {
    const auto t = quantise(T.translation()[i], kMetre, kTranslationLimit);
    const auto r = quantise(phi[i], kRadian, kRotationLimit);
    if (!t || !r) return std::nullopt;
    q[i] = *t;
    q[3 + i] = *r;
  }
  return q;
}

Pose stepOf(const Quantised& q) {
  const Eigen::Vector3d phi(q[3] * kRadian, q[4] * kRadian, q[5] * kRadian);
  Pose T = Pose::Identity();
  const double angle = phi.norm();
  if (angle > 0) T.linear() = Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
  T.translation() = Eigen::Vector3d(q[0] * kMetre, q[1] * kMetre, q[2] * kMetre);
  return T;
}

// A chained bundle is predicted to repeat its predecessor's step (zero when there is none).
Quantised predictedStep(const BundleContext* previous) {
  return previous ? quantiseStep(previous->relative_odom).value_or(Quantised{}) : Quantised{};
}

void writeStep(ByteWriter& w, const Quantised& q, const Quantised& predicted) {
  for (int i = 0; i < 6; ++i) w.svarint(q[i] - predicted[i]);
}

// `predicted`: null when the prediction is not known (the step read is then a residual, only
// checked against twice the limits).
Pose readStep(ByteReader& r, const Quantised* predicted) {
  Quantised q;
  for (int i = 0; i < 6; ++i) {
    const std::int64_t limit = i < 3 ? kTranslationLimit : kRotationLimit;
    const std::int64_t v = r.svarint();
    if (r.ok() && (v < -2 * limit || v > 2 * limit))
      r.fail(std::string("relative odometry ") + (i < 3 ? "translation" : "rotation") + " out of range");
    q[i] = v + (predicted ? (*predicted)[i] : 0);
    if (r.ok() && predicted && (q[i] < -limit || q[i] > limit))
      r.fail(std::string("relative odometry ") + (i < 3 ? "translation" : "rotation") + " out of range");
  }
  if (r.ok() && predicted && std::hypot(q[3], q[4], q[5]) * kRadian > M_PI + 1e-3)
    r.fail("relative odometry rotation exceeds pi");
  return r.ok() ? stepOf(q) : Pose::Identity();
}

// float32 poses (unit quaternion by its three smallest components, or yaw only).
void writePose(ByteWriter& w, const Pose& T) {
  const Eigen::Quaterniond qd(T.rotation());
  Eigen::Vector4f q(static_cast<float>(qd.w()), static_cast<float>(qd.x()), static_cast<float>(qd.y()),
                    static_cast<float>(qd.z()));
  if (q[1] == 0.0f && q[2] == 0.0f) {  // rotation about z only: tag 4, then (w, z) with w >= 0
    if (q[0] < 0) q = -q;
    w.u8(4);
    w.f32(q[0]);
    w.f32(q[3]);
  } else {  // tag: index of the dropped (largest) component, made positive
    int big = 0;
    for (int i = 1; i < 4; ++i)
      if (std::abs(q[i]) > std::abs(q[big])) big = i;
    if (q[big] < 0) q = -q;
    w.u8(static_cast<std::uint8_t>(big));
    for (int i = 0; i < 4; ++i)
      if (i != big) w.f32(q[i]);
  }
  for (int i = 0; i < 3; ++i) w.f32(static_cast<float>(T.translation()[i]));
}

Pose readPose(ByteReader& r, const char* what) {
  const std::uint8_t tag = r.u8();
  if (r.ok() && tag > 4) r.fail(std::string(what) + ": rotation tag " + std::to_string(tag) + " invalid");
  double c[4] = {0, 0, 0, 0};
  double sq = 0;
  for (int i = 0; i < 4; ++i) {
    if (tag == 4 ? (i == 1 || i == 2) : i == tag) continue;  // left out
    const float v = r.f32();
    if (r.ok() && !std::isfinite(v)) r.fail(std::string(what) + ": non-finite quaternion component");
    c[i] = v;
    sq += c[i] * c[i];
  }
  if (r.ok() && tag != 4) {
    if (sq > 1.0 + 1e-4) r.fail(std::string(what) + ": quaternion components exceed unit norm");
    c[tag] = std::sqrt(std::max(0.0, 1.0 - sq));
  }
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) {
    const float v = r.f32();
    if (r.ok() && !std::isfinite(v)) r.fail(std::string(what) + ": non-finite translation");
    t[i] = v;
  }
  const Eigen::Quaterniond q(c[0], c[1], c[2], c[3]);
  if (r.ok() && !(q.norm() >= 0.5)) r.fail(std::string(what) + ": invalid rotation");
  Pose T = Pose::Identity();
  if (!r.ok()) return T;
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

using SigmaCodes = std::array<std::uint8_t, 6>;

// Sigmas travel as float32 (keypose_bundle_t): quantised from their float values.
std::optional<SigmaCodes> quantiseSigmas(const Vector6d& sigma) {
  SigmaCodes q;
  for (int i = 0; i < 6; ++i) {
    const auto c = quantiseSigma(static_cast<float>(sigma[i]));
    if (!c) return std::nullopt;
    q[i] = *c;
  }
  return q;
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

BundleContext BundleContext::of(const KeyPoseBundle& b, const BundleContext* chained_to) {
  return {b.utime, b.odom_pose, b.odom_sigma, b.relative_odom, chained_to ? wrappingSub(b.utime, chained_to->utime) : 0};
}

Bytes encodeBundle(const KeyPoseBundle& b, const BundleContext* previous, BundleDetail detail) {
  const bool team = detail == BundleDetail::Team;
  std::optional<Quantised> chained_step;
  if (!b.first && b.gap == 0 && previous) {
    const Pose step = previous->odom_pose.inverse() * b.odom_pose;
    if ((step.translation() - b.relative_odom.translation()).norm() <= kChainTranslationTol &&
        (step.linear() - b.relative_odom.linear()).norm() <= kChainRotationTol)
      chained_step = quantiseStep(step);
  }
  const std::optional<Quantised> relative = chained_step ? chained_step : quantiseStep(b.relative_odom);
  // Sigma is left out when it is zero (self-contained) or, chained, quantises as the previous.
  const std::optional<SigmaCodes> sigma_codes = quantiseSigmas(b.odom_sigma);
  const std::optional<SigmaCodes> implied = chained_step ? quantiseSigmas(previous->odom_sigma) : SigmaCodes{};
  const bool sigma = !sigma_codes || !implied || *sigma_codes != *implied;
  ByteWriter w;
  w.u8(kBundleFormat);
  w.u8(static_cast<std::uint8_t>((b.first ? kFirst : 0) | (sigma ? kHasSigma : 0) | (chained_step ? kChained : 0) |
                                 (relative ? 0 : kRelativeFloat) | (sigma && !sigma_codes ? kSigmaFloat : 0) |
                                 (team ? kTeam : 0) | (b.gap > 0 ? kGap : 0)));
  if (b.gap > 0) w.svarint(b.gap);
  if (chained_step) {
    w.svarint(wrappingSub(wrappingSub(b.utime, previous->utime), previous->dt));
  } else {
    w.svarint(b.utime);
    writePose(w, b.odom_pose);
  }
  if (relative) writeStep(w, *relative, predictedStep(chained_step ? previous : nullptr));
  else writePose(w, b.relative_odom);
  if (sigma && sigma_codes)
    for (std::uint8_t q : *sigma_codes) w.u8(q);
  else if (sigma)
    for (double s : b.odom_sigma) w.f32(static_cast<float>(s));
  writeObjects(w, b.objects, team ? ObjectListKind::TeamBundle : ObjectListKind::Bundle);
  return w.take();
}

std::optional<KeyPoseBundle> decodeBundle(const Bytes& data, std::int32_t origin, std::int32_t seq, std::string* error,
                                   const BundleContext* previous, bool* needs_previous) {
  ByteReader r(data);
  KeyPoseBundle b;
  b.robot = origin;
  b.seq = seq;
  const std::uint8_t format = r.u8();
  if (r.ok() && format != kBundleFormat) r.fail("unknown bundle format " + std::to_string(format));
  const std::uint8_t flags = r.u8();
  if (r.ok() && (flags & ~kAllFlags)) r.fail("unknown bundle flags " + std::to_string(flags));
  if (r.ok() && (flags & kFirst) && (flags & kChained)) r.fail("first bundle cannot refer to a previous one");
  if (r.ok() && (flags & kChained) && (flags & kRelativeFloat)) r.fail("chained bundle with a float32 step");
  if (r.ok() && (flags & kGap) && (flags & (kFirst | kChained)))
    r.fail("a bundle after a gap is neither first nor chained");
  if (flags & kGap) {
    const std::int64_t gap = r.svarint();
    if (r.ok() && (gap < 1 || gap > std::int64_t{seq} - INT32_MIN)) r.fail("gap length out of range");
    b.gap = static_cast<std::int32_t>(std::min<std::int64_t>(gap, INT32_MAX));
  }
  const bool chained = flags & kChained;
  b.first = flags & kFirst;
  const std::int64_t utime = r.svarint();
  if (!chained) b.odom_pose = readPose(r, "odometry pose");
  const Quantised predicted = predictedStep(chained ? previous : nullptr);
  b.relative_odom = (flags & kRelativeFloat) ? readPose(r, "relative odometry")
                                             : readStep(r, chained && !previous ? nullptr : &predicted);
  if (chained && previous) {
    b.utime = wrappingAdd(wrappingAdd(previous->utime, previous->dt), utime);
    b.odom_pose = previous->odom_pose * b.relative_odom;
    b.odom_sigma = previous->odom_sigma;
  } else if (!chained) {
    b.utime = utime;
  }
  if (needs_previous) *needs_previous = chained && !previous;
  if (r.ok() && (flags & kSigmaFloat) && !(flags & kHasSigma)) r.fail("float32 sigma flag without a sigma");
  if (flags & kSigmaFloat) {
    for (double& s : b.odom_sigma) {
      s = r.f32();
      if (r.ok() && !std::isfinite(s)) r.fail("non-finite odometry sigma");
    }
  } else if (flags & kHasSigma) {
    for (double& s : b.odom_sigma) s = static_cast<float>(sigmaOf(r.u8()));
  }
  readObjects(r, &b.objects, (flags & kTeam) ? ObjectListKind::TeamBundle : ObjectListKind::Bundle);
  return finish(r, std::move(b), error);
}

bool chainedBundle(const Bytes& data) { return data.size() >= 2 && data[0] == kBundleFormat && (data[1] & kChained); }

Bytes encodeMap(const SharedMap& m) {
  ByteWriter w;
  w.u8(kMapFormat);
  w.svarint(m.utime);
  w.svarint(m.frame_robot);
  writeObjects(w, m.objects, ObjectListKind::Map);
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
  if (r.ok() && (frame < INT32_MIN || frame > INT32_MAX)) r.fail("frame robot out of range");
  m.frame_robot = static_cast<std::int32_t>(frame);
  readObjects(r, &m.objects, ObjectListKind::Map);
  return finish(r, std::move(m), error);
}

Bytes encodeMapDelta(const MapDelta& d) {
  ByteWriter w;
  w.u8(kMapDeltaFormat);
  w.svarint(d.base);
  w.svarint(d.utime);
  w.svarint(d.frame_robot);
  w.varint(d.removed.size());
  std::int64_t prev = 0;
  for (std::int64_t id : d.removed) {  // ascending ids as differences
    w.svarint(id - prev);
    prev = id;
  }
  writeObjects(w, d.changed, ObjectListKind::Map);
  return w.take();
}

std::optional<MapDelta> decodeMapDelta(const Bytes& data, std::string* error) {
  ByteReader r(data);
  MapDelta d;
  const std::uint8_t format = r.u8();
  if (r.ok() && format != kMapDeltaFormat) r.fail("unknown map delta format " + std::to_string(format));
  const std::int64_t base = r.svarint(), utime = r.svarint(), frame = r.svarint();
  if (r.ok() && (base < 1 || base > INT32_MAX)) r.fail("base version out of range");
  if (r.ok() && (frame < INT32_MIN || frame > INT32_MAX)) r.fail("frame robot out of range");
  d.base = static_cast<std::int32_t>(base);
  d.utime = utime;
  d.frame_robot = static_cast<std::int32_t>(frame);
  const std::uint64_t n = r.varint();
  if (r.ok() && n > data.size()) r.fail("removed count beyond the payload");
  std::int64_t id = 0;
  for (std::uint64_t i = 0; r.ok() && i < n; ++i) {
    id += r.svarint();
    d.removed.push_back(id);
  }
  readObjects(r, &d.changed, ObjectListKind::Map);
  return finish(r, std::move(d), error);
}

}  // namespace slide::team
