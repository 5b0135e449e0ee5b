// The hardened LCM decoders (cmake/lcm_gen_checked.cmake) against hostile bytes: for every
// type a daemon subscribes to, a hostile length at every position, random flips and every
// truncation must make decode() return -1 or a size within the buffer, never throw, crash
// or allocate beyond what the datagram could hold.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include "hostile_messages.h"

using namespace slide;
using namespace slide::fuzz;

namespace {

// A decode that tries to allocate gigabytes fails here instead of swapping the machine.
struct AddressSpaceCap {
  rlimit old{};
  AddressSpaceCap() {
    getrlimit(RLIMIT_AS, &old);
    rlimit cap = old;
    cap.rlim_cur = std::min<rlim_t>(old.rlim_max, rlim_t{4} << 30);
    setrlimit(RLIMIT_AS, &cap);
  }
  ~AddressSpaceCap() { setrlimit(RLIMIT_AS, &old); }
};

template <class M>
void expectSafe(const M& sample, std::uint32_t seed) {
  const Bytes valid = encode(sample);
  {
    M m;
    ASSERT_EQ(m.decode(valid.data(), 0, static_cast<int>(valid.size())), static_cast<int>(valid.size()));
  }
  AddressSpaceCap cap;
  Mutator mut(seed);
  std::vector<Bytes> variants = mut.hostileLengths(valid);
  for (int i = 0; i < 300; ++i) variants.push_back(mut.flipped(valid, 1 + i % 4));
  for (int i = 0; i < 100; ++i) variants.push_back(mut.truncated(valid));
  int refused = 0;
  for (const Bytes& b : variants) {
    M m;
    int n = 0;
    ASSERT_NO_THROW(n = m.decode(b.data(), 0, static_cast<int>(b.size()))) << M::getTypeName();
    ASSERT_LE(n, static_cast<int>(b.size())) << M::getTypeName();
    refused += n < 0;
  }
  EXPECT_GT(refused, 0) << M::getTypeName() << ": no variant was refused, so none had a hostile length";
}

}  // namespace

TEST(HostileDecode, EveryInputTypeRefusesHostileLengthsWithoutThrowingOrReadingPastTheBuffer) {
  expectSafe(bundle(0, 1), 1);
  expectSafe(objectMap(0), 2);
  expectSafe(trajectory(0), 3);
  expectSafe(loopClosure(0), 4);
  expectSafe(scan(0, 1), 5);
  expectSafe(rgbd(0, 1), 6);
  expectSafe(odometry(0, 1), 7);
  expectSafe(instances(0, 1), 8);
  expectSafe(heartbeat(1), 9);
  expectSafe(chunk(1), 10);
  expectSafe(ack(1, 2), 11);
  expectSafe(orders("fuzz-other"), 12);
  expectSafe(discovery(), 13);
  expectSafe(deputyInfo("fuzz-other"), 14);
}

// The cases of issue 16 finding 1, by hand: lengths of -1, 2^31-1 and the 2^29 / 2^28 that
// overflow lcm_coretypes.h's `int total_size = sizeof(T) * elements`.
TEST(HostileDecode, LengthsThatOverflowLcmsOwnSizeCheckAreRefused) {
  AddressSpaceCap cap;
  for (std::int32_t n : {-1, 0x7fffffff, 1 << 29, (1 << 29) + 1, 1 << 28, 1 << 30}) {
    trajectory_t t = trajectory(0);
    Bytes b = encode(t);
    // num_poses follows the fingerprint (8), utime (8), robot (4), frame_robot (4).
    for (int i = 0; i < 4; ++i) b[24 + i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(n) >> (24 - 8 * i));
    trajectory_t m;
    EXPECT_EQ(m.decode(b.data(), 0, static_cast<int>(b.size())), -1) << "num_poses " << n;
  }
  sync_chunk_t c = chunk(1);
  Bytes b = encode(c);
  const std::size_t size_at = 8 + 2 + 2 + 8 + 1 + 2 + 4 + 2 + 2;
  b[size_at] = 0xff, b[size_at + 1] = 0xff;  // size -1
  sync_chunk_t m;
  EXPECT_EQ(m.decode(b.data(), 0, static_cast<int>(b.size())), -1);
  procman_lcm::discovery_t d = discovery();
  Bytes db = encode(d);
  for (int i = 0; i < 4; ++i) db[16 + i] = 0;  // string length 0 (it counts the NUL: at least 1)
  procman_lcm::discovery_t dm;
  EXPECT_EQ(dm.decode(db.data(), 0, static_cast<int>(db.size())), -1);
}
