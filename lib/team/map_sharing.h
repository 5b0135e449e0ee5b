#pragma once
// Map sharing of the peer-sync protocol. A robot's own object map goes to its peers whole
// while some peer in reach holds none of the versions it still knows, and otherwise as the
// changes against the oldest version those peers hold (codec.h MapDelta): objects new, gone,
// or moved or resized by more than a threshold. Peers announce the versions they hold in
// their heartbeats. Both sides keep the maps exactly as a receiver rebuilds them (quantised,
// unchanged objects left as they were), so sender and receivers agree bit for bit on every
// version. Pure logic, no clock: PeerSyncNode decides when to send.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <variant>
#include <vector>

#include "team/byte_io.h"
#include "team/codec.h"
#include "team/drop_reason.h"
#include "team/messages.h"
#include "team/shared_map.h"

namespace slide::team {

struct MapSharingParams {
  double move_m = 0.1;        // an object moved (centre) or resized (extent) by more is sent again
  double turn_deg = 5.0;      // a cuboid turned by more is sent again
  std::size_t versions = 4;   // versions kept per robot as bases for changes
};

class MapSharing {
 public:
  explicit MapSharing(MapSharingParams p = {}) : p_(p) {}

  // ---- sender ----
  // The robot's own map, its version already assigned (increasing).
  void setOwn(SharedMap m);
  const std::optional<SharedMap>& own() const { return own_; }
  struct Outgoing {
    ChunkKind kind = ChunkKind::Map;  // Map or MapDelta
    std::int32_t version = 0;
    std::int32_t base = 0;  // MapDelta: the version it changes
    Bytes payload;
  };
  // The latest own map for peers holding `held` (each peer in reach's latest announced
  // version of it, 0 for none): changes against the oldest of them when every one is a
  // version kept here, else the whole map. Nothing without an own map.
  std::optional<Outgoing> next(const std::vector<std::int32_t>& held) const;
  // Records `o` as sent: its version, as receivers rebuild it, becomes a base for later changes.
  void sent(const Outgoing& o);

  // ---- receiver ----
  // A whole map or changes of `origin`'s map numbered `version`; returns the map now held, or
  // why nothing changed (Stale: not newer than the one held; MapBaseMissing: changes against a
  // version not kept here; Malformed: undecodable or inconsistent).
  std::variant<SharedMap, Drop> receive(ChunkKind kind, std::int32_t origin, std::int32_t version, const Bytes& payload);
  // Latest version held per robot (for heartbeats), and of one robot (0: none).
  std::map<std::int32_t, std::int32_t> held() const;
  std::int32_t heldVersion(std::int32_t robot) const;
  // Objects in the latest map of `robot` (own or received).
  std::size_t landmarks(std::int32_t robot) const;

 private:
  using Versions = std::deque<SharedMap>;  // oldest first, as receivers rebuild them
  void keep(Versions& v, SharedMap m) const;
  const SharedMap* find(const Versions& v, std::int32_t version) const;
  // `next` as a receiver rebuilds it from `base` and the changes between them.
  MapDelta changes(const SharedMap& base, const SharedMap& next) const;

  MapSharingParams p_;
  std::optional<SharedMap> own_;
  Versions own_sent_;
  std::map<std::int32_t, Versions> received_;
};

// Applies `d` to `base` (objects by id; the result ordered by id). False when an id is not
// unique or a removed id is not in the base.
bool applyMapDelta(const SharedMap& base, const MapDelta& d, std::int32_t version, SharedMap* out);

}  // namespace slide::team
