#include "team/map_sharing.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "team/codec.h"

namespace slide::team {

namespace {

void orderById(SharedMap& m) {
  std::stable_sort(m.objects.begin(), m.objects.end(), [](const Object& a, const Object& b) { return a.id < b.id; });
}

bool uniqueIds(const std::vector<Object>& objects) {
  std::set<std::int64_t> ids;
  for (const Object& o : objects)
    if (o.id < 0 || !ids.insert(o.id).second) return false;
  return true;
}

double yawOf(const Object& o) {
  if (const auto* c = std::get_if<Cuboid>(&o.model)) return std::atan2(c->pose.linear()(1, 0), c->pose.linear()(0, 0));
  return 0.0;
}

}  // namespace

bool applyMapDelta(const SharedMap& base, const MapDelta& d, std::int32_t version, SharedMap* out) {
  std::map<std::int64_t, Object> by_id;
  for (const Object& o : base.objects)
    if (!by_id.emplace(o.id, o).second) return false;
  for (std::int64_t id : d.removed)
    if (by_id.erase(id) == 0) return false;
  std::set<std::int64_t> changed;
  for (const Object& o : d.changed) {
    if (o.id < 0 || !changed.insert(o.id).second) return false;
    by_id[o.id] = o;
  }
  out->robot = base.robot;
  out->frame_robot = d.frame_robot;
  out->version = version;
  out->utime = d.utime;
  out->objects.clear();
  for (auto& [id, o] : by_id) out->objects.push_back(std::move(o));
  return true;
}

void MapSharing::setOwn(SharedMap m) { own_ = std::move(m); }

MapDelta MapSharing::changes(const SharedMap& base, const SharedMap& next) const {
  MapDelta d;
  d.base = base.version;
  d.utime = next.utime;
  d.frame_robot = next.frame_robot;
  std::map<std::int64_t, const Object*> before;
  for (const Object& o : base.objects) before[o.id] = &o;
  std::set<std::int64_t> present;
  for (const Object& o : next.objects) {
    present.insert(o.id);
    const auto it = before.find(o.id);
    bool same = it != before.end();
    if (same) {
      const Object& b = *it->second;
      const double turn = std::abs(std::remainder(yawOf(o) - yawOf(b), 2 * M_PI)) * 180.0 / M_PI;
      same = b.class_id == o.class_id && b.shape() == o.shape() && (b.position() - o.position()).norm() <= p_.move_m &&
             (b.extent() - o.extent()).cwiseAbs().maxCoeff() <= p_.move_m && turn <= p_.turn_deg;
    }
    if (!same) d.changed.push_back(o);
  }
  for (const auto& [id, o] : before)
    if (!present.count(id)) d.removed.push_back(id);
  return d;
}

std::optional<MapSharing::Outgoing> MapSharing::next(const std::vector<std::int32_t>& held) const {
  if (!own_) return std::nullopt;
  Outgoing whole;
  whole.kind = ChunkKind::Map;
  whole.version = own_->version;
  whole.payload = encodeMap(*own_);
  if (held.empty() || !uniqueIds(own_->objects)) return whole;
  const std::int32_t oldest = *std::min_element(held.begin(), held.end());
  const SharedMap* base = find(own_sent_, oldest);
  if (!base || oldest >= own_->version) return whole;
  std::string error;
  std::optional<SharedMap> quantised = decodeMap(whole.payload, own_->robot, own_->version, &error);
  if (!quantised) return whole;
  orderById(*quantised);
  Outgoing delta;
  delta.kind = ChunkKind::MapDelta;
  delta.version = own_->version;
  delta.base = oldest;
  delta.payload = encodeMapDelta(changes(*base, *quantised));
  return delta.payload.size() < whole.payload.size() ? delta : whole;
}

void MapSharing::sent(const Outgoing& o) {
  if (!own_) return;
  std::variant<SharedMap, Drop> rebuilt = Drop::Malformed;
  std::string error;
  if (o.kind == ChunkKind::Map) {
    if (auto m = decodeMap(o.payload, own_->robot, o.version, &error)) {
      orderById(*m);
      rebuilt = std::move(*m);
    }
  } else if (const SharedMap* base = find(own_sent_, o.base)) {
    SharedMap m;
    if (auto d = decodeMapDelta(o.payload, &error); d && applyMapDelta(*base, *d, o.version, &m)) rebuilt = std::move(m);
  }
  if (auto* m = std::get_if<SharedMap>(&rebuilt)) keep(own_sent_, std::move(*m));
}

std::variant<SharedMap, Drop> MapSharing::receive(ChunkKind kind, std::int32_t origin, std::int32_t version,
                                                  const Bytes& payload) {
  if (version <= heldVersion(origin)) return Drop::Stale;
  Versions& held = received_[origin];
  std::string error;
  SharedMap m;
  if (kind == ChunkKind::Map) {
    std::optional<SharedMap> whole = decodeMap(payload, origin, version, &error);
    if (!whole) return Drop::Malformed;
    m = std::move(*whole);
    orderById(m);
  } else {
    const std::optional<MapDelta> d = decodeMapDelta(payload, &error);
    if (!d) return Drop::Malformed;
    const SharedMap* base = find(held, d->base);
    if (!base) return Drop::MapBaseMissing;
    if (!applyMapDelta(*base, *d, version, &m)) return Drop::Malformed;
  }
  keep(held, m);
  return m;
}

std::map<std::int32_t, std::int32_t> MapSharing::held() const {
  std::map<std::int32_t, std::int32_t> out;
  for (const auto& [origin, v] : received_)
    if (!v.empty()) out[origin] = v.back().version;
  return out;
}

std::int32_t MapSharing::heldVersion(std::int32_t robot) const {
  const auto it = received_.find(robot);
  return it == received_.end() || it->second.empty() ? 0 : it->second.back().version;
}

std::size_t MapSharing::landmarks(std::int32_t robot) const {
  if (own_ && own_->robot == robot) return own_->objects.size();
  const auto it = received_.find(robot);
  return it == received_.end() || it->second.empty() ? 0 : it->second.back().objects.size();
}

void MapSharing::keep(Versions& v, SharedMap m) const {
  v.push_back(std::move(m));
  while (v.size() > std::max<std::size_t>(1, p_.versions)) v.pop_front();
}

const SharedMap* MapSharing::find(const Versions& v, std::int32_t version) const {
  for (const SharedMap& m : v)
    if (m.version == version) return &m;
  return nullptr;
}

}  // namespace slide::team
