// The demo report's team-traffic split (tools/demo_report/run_log.h), on a small recorded team bus.
#include <gtest/gtest.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>

#include "run_log.h"
#include "app/channels.h"
#include "slide/sync_chunk_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "team/messages.h"

using namespace slide;

namespace {

template <typename M>
std::size_t write(lcm::LogFile& log, const char* channel, const M& m) {
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  lcm::LogEvent ev{};
  ev.channel = channel;
  ev.datalen = static_cast<int32_t>(buf.size());
  ev.data = buf.data();
  log.writeEvent(&ev);
  return team::lcmWireBytes(channel, buf.size());
}

sync_chunk_t chunk(int sender, int8_t kind, int size) {
  sync_chunk_t c{};
  c.sender = static_cast<int16_t>(sender);
  c.receiver = -1;
  c.kind = kind;
  c.origin = static_cast<int16_t>(sender);
  c.num_chunks = 1;
  c.size = static_cast<int16_t>(size);
  c.data.assign(static_cast<std::size_t>(size), 7);
  return c;
}

}  // namespace

// Whole maps and map changes are maps, not bundles; an unknown chunk kind is undecodable; only
// the recording host's own messages count.
TEST(TeamTraffic, MapChangesCountAsMapsAndOnlyTheSendersOwnMessages) {
  const std::string path = "/tmp/slide_test_team_traffic_" + std::to_string(getpid()) + ".lcmlog";
  std::size_t bundles = 0, maps = 0, heartbeats = 0;
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    bundles += write(log, app::channels::kTeamChunk, chunk(1, sync_chunk_t::BUNDLE, 300));
    maps += write(log, app::channels::kTeamChunk, chunk(1, sync_chunk_t::MAP, 200));
    maps += write(log, app::channels::kTeamChunk, chunk(1, sync_chunk_t::MAP_DELTA, 100));
    write(log, app::channels::kTeamChunk, chunk(2, sync_chunk_t::MAP_DELTA, 100));  // a peer's
    write(log, app::channels::kTeamChunk, chunk(1, 9, 50));                         // no such kind
    sync_heartbeat_t h{};
    h.sender = 1;
    heartbeats += write(log, app::channels::kTeamHeartbeat, h);
  }
  const TeamTraffic t = readTeamTraffic(path, 1);
  std::remove(path.c_str());
  EXPECT_EQ(t.bundles, static_cast<std::int64_t>(bundles));
  EXPECT_EQ(t.maps, static_cast<std::int64_t>(maps));
  EXPECT_EQ(t.heartbeats, static_cast<std::int64_t>(heartbeats));
  EXPECT_EQ(t.acks, 0);
  EXPECT_EQ(t.messages, 4);
  EXPECT_EQ(t.undecodable, 1);
}
