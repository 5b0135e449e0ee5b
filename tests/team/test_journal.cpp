#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include <sys/resource.h>

#include <csignal>

#include "team/counters.h"
#include "team/journal.h"
#include "team/observation_db.h"

using namespace slide::team;
namespace fs = std::filesystem;

namespace {
fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("slide_team_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Bytes payloadOf(int i) { return Bytes(static_cast<std::size_t>(i % 50), static_cast<std::uint8_t>(i)); }
}  // namespace

TEST(Journal, TruncationAtEveryOffsetKeepsEveryCompleteRecord) {
  const fs::path dir = freshDir("journal");
  const std::string path = (dir / "j.bin").string();
  std::vector<std::size_t> ends;  // file size after each record
  {
    Journal j(path, nullptr);
    for (int i = 0; i < 20; ++i) {
      j.append(static_cast<std::uint8_t>(i % 3), payloadOf(i));
      ends.push_back(fs::file_size(path));
    }
  }
  std::ifstream in(path, std::ios::binary);
  const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t cut = 0; cut <= full.size(); ++cut) {
    const std::string p = (dir / ("cut" + std::to_string(cut))).string();
    std::ofstream(p, std::ios::binary).write(full.data(), static_cast<std::streamsize>(cut));
    std::vector<JournalRecord> recs;
    JournalRecovery info;
    {
      Journal j(p, &recs, &info);
      const std::size_t complete = static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), cut) - ends.begin());
      ASSERT_EQ(recs.size(), complete) << "cut at " << cut;
      for (std::size_t i = 0; i < recs.size(); ++i) EXPECT_EQ(recs[i].payload, payloadOf(static_cast<int>(i)));
      EXPECT_EQ(info.dropped_bytes, cut - (complete ? ends[complete - 1] : 0));
      j.append(9, Bytes{1, 2, 3});  // appending continues right after the last good record
    }
    std::vector<JournalRecord> again;
    Journal j2(p, &again);
    ASSERT_FALSE(again.empty());
    EXPECT_EQ(again.back().type, 9);
    EXPECT_EQ(again.size(), recs.size() + 1);
  }
  fs::remove_all(dir);
}

TEST(Journal, CorruptedRecordStopsReplayAndTailIsSavedAside) {
  const fs::path dir = freshDir("corrupt");
  const std::string path = (dir / "j.bin").string();
  {
    Journal j(path, nullptr);
    for (int i = 0; i < 5; ++i) j.append(1, payloadOf(i + 10));
  }
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(path) - 3));
    f.put('\x55');
  }
  std::vector<JournalRecord> recs;
  JournalRecovery info;
  Journal j(path, &recs, &info);
  EXPECT_EQ(recs.size(), 4u);
  EXPECT_GT(info.dropped_bytes, 0u);
  EXPECT_TRUE(fs::exists(info.damaged_copy));
  fs::remove_all(dir);
}

TEST(ObservationDb, RebuildsHoldingsAndDeliveryCursorFromJournal) {
  const fs::path dir = freshDir("db");
  const std::string path = (dir / "journal.bin").string();
  {
    ObservationDb db(path);
    for (int s = 0; s < 10; ++s) ASSERT_TRUE(db.add(1, s, {Bytes{static_cast<std::uint8_t>(s)}, s == 0, 1.5f}));
    EXPECT_FALSE(db.add(1, 3, {Bytes{99}, false, 0}));  // never overwritten
    for (int s = 0; s < 4; ++s) db.markDelivered(1, s);
  }
  // kill -9 in the middle of a record: simulate by appending half a record.
  {
    const Bytes rec = Journal::frame(1, Bytes(40, 7));
    std::ofstream(path, std::ios::binary | std::ios::app).write(reinterpret_cast<const char*>(rec.data()), 20);
  }
  ObservationDb db(path);
  EXPECT_EQ(db.size(), 10u);
  EXPECT_EQ(db.get(1, 3)->data, Bytes{3});
  EXPECT_EQ(db.firstSeq(1), 0);
  EXPECT_NEAR(db.metres(1), 15.0, 1e-6);
  const auto next = db.nextToDeliver(0);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->second, 4);
  EXPECT_FALSE(db.nextToDeliver(1));  // origin 1 skipped (own)
  EXPECT_GT(db.recovery().dropped_bytes, 0u);
  fs::remove_all(dir);
}

TEST(CounterStore, OwnCountersGrowAcrossRestartsAndAcceptedPersist) {
  const fs::path dir = freshDir("counters");
  const std::string path = (dir / "c.txt").string();
  std::int64_t last = 0;
  {
    CounterStore c(path);
    for (int i = 0; i < 10; ++i) last = c.nextOwn();
    EXPECT_TRUE(c.accept(3, 100));
    EXPECT_FALSE(c.accept(3, 100));
    EXPECT_FALSE(c.accept(3, 50));
    c.save();
  }
  CounterStore c(path);
  EXPECT_GT(c.nextOwn(), last);
  EXPECT_FALSE(c.accept(3, 100));
  EXPECT_TRUE(c.accept(3, 101));
  EXPECT_FALSE(c.accept(3, 99));  // at or below the persisted highest: too old to tell
  std::ofstream(path) << "own x\n";
  CounterStore bad(path);  // skipped with a warning (test_peer_sync_full_disk.cpp), not fatal
  EXPECT_EQ(bad.warnings().size(), 1u);
  fs::remove_all(dir);
}

TEST(CounterStore, ReorderedCountersWithinTheWindowAreTakenOnce) {
  CounterStore c("");
  EXPECT_TRUE(c.accept(3, 1000));
  EXPECT_TRUE(c.accept(3, 1005));
  EXPECT_TRUE(c.accept(3, 1003));  // overtaken in flight
  EXPECT_FALSE(c.accept(3, 1003));
  EXPECT_FALSE(c.accept(3, 1000));
  EXPECT_FALSE(c.accept(3, 1005));
  EXPECT_TRUE(c.accept(3, 1001));
  EXPECT_TRUE(c.accept(3, 1005 + CounterStore::kWindow - 1));
  EXPECT_TRUE(c.accept(3, 1004));  // still inside the window
  EXPECT_FALSE(c.accept(3, 1002 + CounterStore::kWindow - 1 - CounterStore::kWindow));  // 1001 again
  EXPECT_TRUE(c.accept(3, 1200));
  EXPECT_FALSE(c.accept(3, 1200 - CounterStore::kWindow - 1));  // beyond the window
  EXPECT_TRUE(c.accept(3, 1200 - CounterStore::kWindow));     // the window's oldest, never seen
  EXPECT_FALSE(c.accept(3, 1200 - CounterStore::kWindow));
  EXPECT_TRUE(c.accept(3, 1264));
  EXPECT_FALSE(c.accept(3, 1200));  // now exactly kWindow below and seen
  EXPECT_EQ(c.lastAccepted(3), 1264);
}

TEST(Journal, ARecordWhoseReplayThrowsIsSkippedAndCountedAndTheOthersReplayed) {
  std::vector<JournalRecord> records;
  for (int i = 0; i < 5; ++i) records.push_back({1, payloadOf(i + 1)});
  std::vector<int> used;
  JournalRecovery info;
  const std::size_t n = replayRecords(
      records,
      [&](const JournalRecord& r) -> std::string {
        if (r.payload.size() == 3) throw std::out_of_range("no such key pose");
        if (r.payload.size() == 4) return "not usable";
        used.push_back(static_cast<int>(r.payload.size()));
        return {};
      },
      info);
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(used, (std::vector<int>{1, 2, 5}));
  EXPECT_EQ(info.skipped, 2u);
  EXPECT_EQ(info.first_skipped, "record 3: replay failed: no such key pose");
}

TEST(Journal, AFailedAppendIsCutBackSoLaterRecordsStayReachable) {
  // A file size limit stands in for a full disk: the record is written in part, then the write
  // fails. The torn part must go, or every later record would sit behind it.
  const fs::path dir = freshDir("torn");
  const std::string path = (dir / "j.bin").string();
  Journal j(path, nullptr);
  j.append(1, payloadOf(7));
  const auto size = fs::file_size(path);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  auto* previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = size + 20;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  EXPECT_THROW(j.append(2, Bytes(100, 0xAB)), std::runtime_error);
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_EQ(fs::file_size(path), size);
  j.append(3, payloadOf(9));
  std::vector<JournalRecord> recs;
  JournalRecovery info;
  Journal again(path, &recs, &info);
  ASSERT_EQ(recs.size(), 2u);
  EXPECT_EQ(recs[1].type, 3);
  EXPECT_EQ(info.dropped_bytes, 0u);
  fs::remove_all(dir);
}
