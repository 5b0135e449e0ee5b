#include "team_msg.h"

#include <cmath>

#include "msg/convert.h"

namespace slide::team {
namespace {

std::vector<origin_ranges_t> toLcm(const OriginRanges& r) {
  std::vector<origin_ranges_t> out;
  for (const auto& [origin, set] : r) {
    origin_ranges_t o;
    o.origin = origin;
    for (const auto& x : set.ranges()) {
      seq_range_t s;
      s.first = x.first;
      s.last = x.last;
      o.ranges.push_back(s);
    }
    o.num_ranges = static_cast<int16_t>(o.ranges.size());
    out.push_back(std::move(o));
  }
  return out;
}

// Ranges must be well formed, ascending and disjoint, origins unique: otherwise the MAC of the
// canonical form would not match what the sender signed anyway, but say why.
bool fromLcm(const std::vector<origin_ranges_t>& in, OriginRanges* out, std::string* why) {
  for (const auto& o : in) {
    if (out->count(o.origin)) return *why = "origin " + std::to_string(o.origin) + " listed twice", false;
    std::vector<SeqRange> ranges;
    for (const auto& r : o.ranges) {
      if (r.first > r.last || r.first < 0) return *why = "invalid range for origin " + std::to_string(o.origin), false;
      if (!ranges.empty() && r.first <= ranges.back().last + 1)
        return *why = "ranges of origin " + std::to_string(o.origin) + " overlap or are unsorted", false;
      ranges.push_back({r.first, r.last});
    }
    (*out)[o.origin] = RangeSet::fromRanges(ranges);
  }
  return true;
}

template <typename M>
void copyMac(const M& from, Mac& to) {
  to.assign(from.mac.begin(), from.mac.end());
}

template <typename M>
void setMac(M& to, const Mac& from) {
  to.mac.assign(from.begin(), from.end());
  to.mac_size = static_cast<int8_t>(to.mac.size());
}

// Physical bounds of what a robot reports: coordinates in its odometry frame (1000 km; the
// team codec keeps them in floats), odometry sigmas, object sizes.
constexpr double kMaxCoordinate = 1e6;
constexpr float kMaxSigma = 1e3f;
constexpr double kMaxObjectSize = 1e3;

bool withinFrame(const double (&xyz)[3]) {
  for (double v : xyz)
    if (!(std::abs(v) <= kMaxCoordinate)) return false;
  return true;
}

bool saneObject(const Object& o) {
  return o.position().cwiseAbs().maxCoeff() <= kMaxCoordinate && o.extent().cwiseAbs().maxCoeff() <= kMaxObjectSize;
}


}  // namespace

sync_heartbeat_t toLcm(const Heartbeat& m) {
  sync_heartbeat_t o;
  o.sender = m.sender;
  o.counter = m.counter;
  o.held = toLcm(m.held);
  o.num_origins = static_cast<int16_t>(o.held.size());
  for (const auto& [origin, version] : m.maps) {
    map_version_t v;
    v.origin = static_cast<int16_t>(origin);
    v.version = version;
    o.maps.push_back(v);
  }
  o.num_maps = static_cast<int16_t>(o.maps.size());
  setMac(o, m.mac);
  return o;
}

sync_chunk_t toLcm(const Chunk& m) {
  sync_chunk_t o;
  o.sender = m.sender;
  o.receiver = m.receiver;
  o.counter = m.counter;
  o.kind = static_cast<int8_t>(m.kind);
  o.origin = m.origin;
  o.seq = m.seq;
  o.chunk_index = m.chunk_index;
  o.num_chunks = m.num_chunks;
  o.data = m.data;
  o.size = static_cast<int16_t>(o.data.size());
  setMac(o, m.mac);
  return o;
}

sync_ack_t toLcm(const Ack& m) {
  sync_ack_t o;
  o.sender = m.sender;
  o.receiver = m.receiver;
  o.counter = m.counter;
  o.acked = toLcm(m.acked);
  o.num_origins = static_cast<int16_t>(o.acked.size());
  setMac(o, m.mac);
  return o;
}

std::optional<Heartbeat> fromLcm(const sync_heartbeat_t& m, std::string* why) {
  Heartbeat h;
  h.sender = m.sender;
  h.counter = m.counter;
  if (!fromLcm(m.held, &h.held, why)) return std::nullopt;
  for (const map_version_t& v : m.maps) {
    if (v.origin < 0) return *why = "map of robot " + std::to_string(v.origin), std::nullopt;
    if (v.version < 1) return *why = "map version " + std::to_string(v.version) + " of robot " + std::to_string(v.origin), std::nullopt;
    if (!h.maps.emplace(v.origin, v.version).second)
      return *why = "robot " + std::to_string(v.origin) + "'s map listed twice", std::nullopt;
  }
  copyMac(m, h.mac);
  return h;
}

std::optional<Chunk> fromLcm(const sync_chunk_t& m, std::string* why) {
  if (m.kind != sync_chunk_t::BUNDLE && m.kind != sync_chunk_t::MAP && m.kind != sync_chunk_t::MAP_DELTA)
    return *why = "unknown chunk kind " + std::to_string(m.kind), std::nullopt;
  Chunk c;
  c.sender = m.sender;
  c.receiver = m.receiver;
  c.counter = m.counter;
  c.kind = static_cast<ChunkKind>(m.kind);
  c.origin = m.origin;
  c.seq = m.seq;
  c.chunk_index = m.chunk_index;
  c.num_chunks = m.num_chunks;
  c.data = m.data;
  copyMac(m, c.mac);
  return c;
}

std::optional<Ack> fromLcm(const sync_ack_t& m, std::string* why) {
  Ack a;
  a.sender = m.sender;
  a.receiver = m.receiver;
  a.counter = m.counter;
  if (!fromLcm(m.acked, &a.acked, why)) return std::nullopt;
  copyMac(m, a.mac);
  return a;
}

std::optional<KeyPoseBundle> acceptBundle(const keypose_bundle_t& m, std::string* why) {
  const std::string who = "bundle " + std::to_string(m.header.robot) + "/" + std::to_string(m.header.seq);
  if (!msg::usablePose(m.odom_pose) || !msg::usablePose(m.relative_odom) || !withinFrame(m.odom_pose.position) ||
      !withinFrame(m.relative_odom.position))
    return *why = who + ": invalid odom_pose or relative_odom (non-finite, or beyond " +
                  std::to_string(kMaxCoordinate) + " m)",
           std::nullopt;
  for (float s : m.odom_sigma)
    if (!(s >= 0 && s <= kMaxSigma))
      return *why = who + ": odom_sigma " + std::to_string(s) + " is not in [0, " + std::to_string(kMaxSigma) + "]",
             std::nullopt;
  std::vector<std::string> dropped;
  KeyPoseBundle b = msg::fromLcm(m, &dropped);
  if (!dropped.empty()) return *why = who + ": " + dropped.front(), std::nullopt;
  for (std::size_t i = 0; i < b.objects.size(); ++i) {
    const std::string object = "object " + std::to_string(m.objects[i].id);
    if (!b.objects[i].isFinite()) return *why = who + ": " + object + " has non-finite numbers", std::nullopt;
    if (!saneObject(b.objects[i]))
      return *why = who + ": " + object + " is beyond " + std::to_string(kMaxCoordinate) + " m or absurdly large",
             std::nullopt;
  }
  return b;
}

object_map_t toLcm(const SharedMap& m) {
  object_map_t o;
  o.utime = m.utime;
  o.robot = m.robot;
  o.frame_robot = m.frame_robot;
  for (const auto& obj : m.objects) o.objects.push_back(msg::toLcm(obj));
  o.num_objects = static_cast<int32_t>(o.objects.size());
  return o;
}

std::optional<SharedMap> fromLcm(const object_map_t& m, std::string* why) {
  SharedMap s;
  s.robot = m.robot;
  s.frame_robot = m.frame_robot;
  s.utime = m.utime;
  try {
    for (const auto& o : m.objects) {
      Object obj = msg::fromLcm(o);
      if (!obj.isFinite()) throw std::invalid_argument("object " + std::to_string(o.id) + " has non-finite numbers");
      if (!saneObject(obj)) throw std::invalid_argument("object " + std::to_string(o.id) + " is beyond " +
                                                        std::to_string(kMaxCoordinate) + " m or absurdly large");
      s.objects.push_back(std::move(obj));
    }
  } catch (const std::invalid_argument& e) {
    return *why = std::string("object map: ") + e.what(), std::nullopt;
  }
  return s;
}

}  // namespace slide::team
