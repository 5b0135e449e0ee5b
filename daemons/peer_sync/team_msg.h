#pragma once
// Conversions between the team layer's plain structs and the LCM messages of both buses (a
// key-pose bundle converts in msg/convert.h; acceptBundle checks one from the robot bus).
// Every from*() validates and returns nullopt with a reason instead of throwing.
#include <optional>
#include <string>

#include "msg/convert.h"
#include "objects/keypose_bundle.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/sync_ack_t.hpp"
#include "slide/sync_chunk_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "team/messages.h"
#include "team/shared_map.h"

namespace slide::team {

sync_heartbeat_t toLcm(const Heartbeat& m);
sync_chunk_t toLcm(const Chunk& m);
sync_ack_t toLcm(const Ack& m);
std::optional<Heartbeat> fromLcm(const sync_heartbeat_t& m, std::string* why);
std::optional<Chunk> fromLcm(const sync_chunk_t& m, std::string* why);
std::optional<Ack> fromLcm(const sync_ack_t& m, std::string* why);

// The bundle of `m` (msg/convert.h) when every number is finite and within physical bounds and
// every object has exactly one model; nullopt and why otherwise.
std::optional<KeyPoseBundle> acceptBundle(const keypose_bundle_t& m, std::string* why);
object_map_t toLcm(const SharedMap& m);
std::optional<SharedMap> fromLcm(const object_map_t& m, std::string* why);

// Decodes an LCM message from raw bytes; nullopt when the bytes are not exactly one message.
template <typename T>
std::optional<T> decodeLcm(const void* data, std::size_t size) {
  T m;
  const int n = m.decode(data, 0, static_cast<int>(size));
  if (n < 0 || static_cast<std::size_t>(n) != size) return std::nullopt;
  return m;
}

}  // namespace slide::team
