// The optimizer's journal is checksummed and recoverable (issue 16 finding 5): a damaged tail
// is cut and saved aside at start and inputs accepted after it are replayed at the next
// restart; a flipped bit is detected and its record not replayed; a record that is not an
// input is skipped and counted; the LCM log of older versions is refused, not cut as damage.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>

#include "optimizer_node.h"
#include "scenario_messages.h"

using namespace slide;
using slide::testing::RawMessage;
namespace fs = std::filesystem;

namespace {

std::string freshJournal(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("slide_opt_journal_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return (dir / "optimizer.journal").string();
}

void feed(OptimizerNode& node, const std::vector<RawMessage>& msgs, std::size_t from, std::size_t to) {
  for (std::size_t i = from; i < to; ++i)
    node.handle(msgs[i].channel, msgs[i].bytes.data(), static_cast<int>(msgs[i].bytes.size()));
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Byte offset where journal record `i` starts (header 9 bytes, payload, CRC 4 bytes).
std::size_t recordOffset(const std::string& path, std::size_t i) {
  std::size_t off = 0;
  const auto records = team::Journal::read(path);
  for (std::size_t k = 0; k < i; ++k) off += 9 + records.at(k).payload.size() + 4;
  return off;
}

}  // namespace

TEST(OptimizerJournal, DamagedTailIsCutAndInputsAfterItAreReplayedAtTheNextRestart) {
  const auto msgs = slide::testing::twoRobotMessages();
  const ClassTable classes = ClassTable::loadDefault();
  const std::string path = freshJournal("tail");
  const std::size_t first = 30, second = 60;
  {
    OptimizerNode a(backend::BackendConfig{}, classes, 0, {}, {});
    a.openJournal(path);
    feed(a, msgs, 0, first);
  }
  // A write torn by a crash: half of a record, then nothing.
  const std::string good = readFile(path);
  writeFile(path, good + good.substr(recordOffset(path, 1), 25));
  {
    OptimizerNode b(backend::BackendConfig{}, classes, 0, {}, {});
    EXPECT_EQ(b.openJournal(path), static_cast<int>(first));
    EXPECT_EQ(b.journalRecovery().dropped_bytes, 25u);
    EXPECT_TRUE(fs::exists(b.journalRecovery().damaged_copy));
    feed(b, msgs, first, second);
  }
  OptimizerNode c(backend::BackendConfig{}, classes, 0, {}, {});
  EXPECT_EQ(c.openJournal(path), static_cast<int>(second));  // appended after the last good record
  EXPECT_EQ(c.journalRecovery().dropped_bytes, 0u);
  OptimizerNode clean(backend::BackendConfig{}, classes, 0, {}, {});
  feed(clean, msgs, 0, second);
  EXPECT_EQ(c.optimizer().numKeyPoses(), clean.optimizer().numKeyPoses());
  fs::remove_all(fs::path(path).parent_path());
}

TEST(OptimizerJournal, AFlippedBitIsDetectedAndItsRecordNotReplayed) {
  const auto msgs = slide::testing::twoRobotMessages();
  const ClassTable classes = ClassTable::loadDefault();
  const std::string path = freshJournal("flip");
  {
    OptimizerNode a(backend::BackendConfig{}, classes, 0, {}, {});
    a.openJournal(path);
    feed(a, msgs, 0, 20);
  }
  // One bit inside record 12's payload (a bundle): replayed as data, it would be a wrong pose.
  std::string bytes = readFile(path);
  bytes[recordOffset(path, 11) + 9 + 40] ^= 0x10;
  writeFile(path, bytes);
  OptimizerNode b(backend::BackendConfig{}, classes, 0, {}, {});
  EXPECT_EQ(b.openJournal(path), 11);
  EXPECT_GT(b.journalRecovery().dropped_bytes, 0u);
  EXPECT_EQ(readFile(b.journalRecovery().damaged_copy), bytes.substr(recordOffset(path, 11)));
  OptimizerNode clean(backend::BackendConfig{}, classes, 0, {}, {});
  feed(clean, msgs, 0, 11);
  EXPECT_EQ(b.optimizer().numKeyPoses(), clean.optimizer().numKeyPoses());
  fs::remove_all(fs::path(path).parent_path());
}

TEST(OptimizerJournal, ARecordThatIsNoInputIsSkippedAndCountedAndTheRestReplayed) {
  const auto msgs = slide::testing::twoRobotMessages();
  const ClassTable classes = ClassTable::loadDefault();
  const std::string path = freshJournal("skip");
  {
    OptimizerNode a(backend::BackendConfig{}, classes, 0, {}, {});
    a.openJournal(path);
    feed(a, msgs, 0, 10);
  }
  {
    team::Journal j(path, nullptr);
    j.append(77, team::Bytes{1, 2, 3});  // a record type of some other version
  }
  {
    OptimizerNode a(backend::BackendConfig{}, classes, 0, {}, {});
    a.openJournal(path);
    feed(a, msgs, 10, 20);
  }
  OptimizerNode b(backend::BackendConfig{}, classes, 0, {}, {});
  EXPECT_EQ(b.openJournal(path), 20);
  EXPECT_EQ(b.replaySkipped(), 1);
  EXPECT_NE(b.journalRecovery().first_skipped.find("record 11: unknown record type 77"), std::string::npos)
      << b.journalRecovery().first_skipped;
  fs::remove_all(fs::path(path).parent_path());
}

TEST(OptimizerJournal, TheLcmLogOfOlderVersionsIsRefusedWithAClearMessageAndLeftAlone) {
  const auto msgs = slide::testing::twoRobotMessages();
  const std::string path = freshJournal("old");
  {
    lcm::LogFile log(path, "w");
    lcm::LogEvent e{};
    e.channel = msgs[0].channel;
    e.datalen = static_cast<int32_t>(msgs[0].bytes.size());
    e.data = const_cast<uint8_t*>(msgs[0].bytes.data());
    ASSERT_EQ(log.writeEvent(&e), 0);
  }
  const std::string before = readFile(path);
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {}, {});
  try {
    node.openJournal(path);
    FAIL() << "an LCM log was taken as a journal";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + " is not a slide journal"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readFile(path), before);
  fs::remove_all(fs::path(path).parent_path());
}
