#pragma once
// The three team-bus messages as plain structs (the daemon maps them 1:1 onto
// sync_heartbeat_t, sync_chunk_t and sync_ack_t), and their encoded sizes on the wire.
#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "team/byte_io.h"
#include "team/seq_ranges.h"

namespace slide::team {

using Mac = Bytes;  // the per-member tags (message_auth.h)

struct Heartbeat {
  std::int32_t sender = 0;
  std::int64_t counter = 0;
  OriginRanges held;  // what the sender holds, per origin (its own bundles once sent)
  std::map<std::int32_t, std::int32_t> maps;  // peers' map versions the sender holds, by robot
  Mac mac{};
};

// Map: a whole object map; MapDelta: its changes against a version the peers hold (codec.h).
enum class ChunkKind : std::int8_t { Bundle = 0, Map = 1, MapDelta = 2 };

struct Chunk {
  std::int32_t sender = 0;
  std::int32_t receiver = -1;  // -1: everyone
  std::int64_t counter = 0;
  ChunkKind kind = ChunkKind::Bundle;
  std::int32_t origin = 0;
  std::int32_t seq = 0;  // bundle sequence number, or map version for kind Map
  std::int16_t chunk_index = 0;
  std::int16_t num_chunks = 1;
  Bytes data;
  Mac mac{};
};

struct Ack {
  std::int32_t sender = 0;    // who acknowledges
  std::int32_t receiver = 0;  // whose bookmark this updates
  std::int64_t counter = 0;
  OriginRanges acked;
  Mac mac{};
};

// Bytes of the LCM encoding (fingerprint included) of each message.
std::size_t encodedSize(const Heartbeat& m);
std::size_t encodedSize(const Chunk& m);
std::size_t encodedSize(const Ack& m);
// Bytes one LCM message of `payload` encoded bytes on `channel` puts on an IPv4 network, as
// Linux's LCM sends it over UDP multicast: one datagram (8-byte LCM header, channel, NUL,
// payload) while channel, NUL and payload fit 65,499 bytes, else fragments of at most 65,487
// bytes behind a 20-byte header each (the channel in the first); every datagram then adds its
// UDP header (8) and one IPv4 header (20) per IP fragment of at most `mtu` bytes. Link-layer
// framing is not counted.
std::size_t lcmWireBytes(const std::string& channel, std::size_t payload, std::size_t mtu = 1500);

}  // namespace slide::team
