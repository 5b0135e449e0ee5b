#include <gtest/gtest.h>

#include <random>
#include <set>

#include "team/seq_ranges.h"

using namespace slide::team;

TEST(RangeSet, MatchesStdSetUnderRandomInserts) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    RangeSet rs;
    std::set<std::int32_t> ref;
    for (int i = 0; i < 300; ++i) {
      if (rng() % 3 == 0) {
        const std::int32_t a = static_cast<std::int32_t>(rng() % 500), b = a + static_cast<std::int32_t>(rng() % 10);
        rs.insert(SeqRange{a, b});
        for (std::int32_t s = a; s <= b; ++s) ref.insert(s);
      } else {
        const auto s = static_cast<std::int32_t>(rng() % 500);
        EXPECT_EQ(rs.insert(s), ref.insert(s).second);
      }
    }
    EXPECT_EQ(rs.count(), static_cast<std::int64_t>(ref.size()));
    for (std::int32_t s = -5; s < 520; ++s) EXPECT_EQ(rs.contains(s), ref.count(s) > 0) << s;
    // Ranges are sorted, disjoint and never adjacent.
    const auto r = rs.ranges();
    for (std::size_t i = 1; i < r.size(); ++i) EXPECT_GT(r[i].first, r[i - 1].last + 1);
    EXPECT_EQ(RangeSet::fromRanges(r), rs);
    // minus() against another random set.
    RangeSet other;
    std::set<std::int32_t> other_ref;
    for (int i = 0; i < 200; ++i) {
      const auto s = static_cast<std::int32_t>(rng() % 500);
      other.insert(s);
      other_ref.insert(s);
    }
    std::vector<std::int32_t> expect;
    for (auto s : ref)
      if (!other_ref.count(s)) expect.push_back(s);
    EXPECT_EQ(rs.minus(other, 100000), expect);
    const auto limited = rs.minus(other, 7);
    EXPECT_EQ(limited, std::vector<std::int32_t>(expect.begin(), expect.begin() + std::min<std::size_t>(7, expect.size())));
  }
}

TEST(RangeSet, ExtremesAndEmptyRanges) {
  RangeSet rs;
  rs.insert(SeqRange{5, 4});  // empty: ignored
  EXPECT_TRUE(rs.empty());
  rs.insert(SeqRange{INT32_MAX - 1, INT32_MAX});
  rs.insert(SeqRange{INT32_MIN, INT32_MIN + 1});
  EXPECT_EQ(rs.count(), 4);
  EXPECT_EQ(rs.max(), INT32_MAX);
  EXPECT_EQ(rs.min(), INT32_MIN);
}

TEST(RangeSet, IntersectsAndRangeOf) {
  const RangeSet s = RangeSet::fromRanges({{0, 4}, {10, 12}});
  EXPECT_TRUE(s.intersects({4, 8}));
  EXPECT_TRUE(s.intersects({-5, 0}));
  EXPECT_TRUE(s.intersects({11, 11}));
  EXPECT_FALSE(s.intersects({5, 9}));
  EXPECT_FALSE(s.intersects({13, 100}));
  EXPECT_EQ(s.rangeOf(11), (SeqRange{10, 12}));
  EXPECT_FALSE(s.rangeOf(7));
  EXPECT_FALSE(s.rangeOf(-1));
}
