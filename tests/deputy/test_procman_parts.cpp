// Exec-string splitting, /proc parsing, output batching.
#include <gtest/gtest.h>
#include <unistd.h>

#include "procman/exec_args.h"
#include "procman/output_batcher.h"
#include "procman/output_lines.h"
#include "procman/proc_stats.h"

using namespace slide::procman;

TEST(ExecArgs, SplitsQuotesEscapesAndEnv) {
  const ExecArgs a = splitExec("FOO=1 BAR='a b' prog --x \"y z\" 'it''s' back\\ slash");
  ASSERT_EQ(a.env.size(), 2u);
  EXPECT_EQ(a.env[1].first, "BAR");
  EXPECT_EQ(a.env[1].second, "a b");
  EXPECT_EQ(a.argv, (std::vector<std::string>{"prog", "--x", "y z", "its", "back slash"}));
  EXPECT_EQ(splitExec("sh -c 'echo a=b'").argv.back(), "echo a=b");
  EXPECT_EQ(splitExec("prog X=1").argv.size(), 2u);  // assignments only lead
}

TEST(ExecArgs, RejectsBadStrings) {
  EXPECT_THROW(splitExec("prog 'open"), std::invalid_argument);
  EXPECT_THROW(splitExec("   "), std::invalid_argument);
  EXPECT_THROW(splitExec("A=1"), std::invalid_argument);
}

TEST(ProcStats, ParsesProcessStatWithSpacesInName) {
  const std::string stat =
      "1234 (my prog) S 1 1234 1234 0 -1 4194560 100 0 0 0 250 75 0 0 20 0 1 0 100 104857600 512 "
      "18446744073709551615 1 1 0 0 0 0 0 0 0 0 0 0 17 0 0 0 0 0 0";
  const auto t = parseProcessStat(stat, 4096);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->user_jiffies, 250u);
  EXPECT_EQ(t->system_jiffies, 75u);
  EXPECT_EQ(t->vsize_bytes, 104857600);
  EXPECT_EQ(t->rss_bytes, 512 * 4096);
  EXPECT_FALSE(parseProcessStat("garbage", 4096));
  EXPECT_FALSE(parseProcessStat("1 (x) S 1 2", 4096));
}

TEST(ProcStats, ParsesSystemStatAndMeminfo) {
  const auto s = parseSystemStat("cpu  100 20 30 850 5 0 0 0 0 0\ncpu0 1 2 3 4\n");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->busy_jiffies, 150u);
  EXPECT_EQ(s->total_jiffies, 1000u);
  EXPECT_FALSE(parseSystemStat("intr 1 2 3"));
  const MemoryInfo m = parseMeminfo("MemTotal: 1000 kB\nMemFree: 100 kB\nMemAvailable: 400 kB\nSwapTotal: 50 kB\nSwapFree: 20 kB\n");
  EXPECT_EQ(m.total_bytes, 1024000);
  EXPECT_EQ(m.free_bytes, 409600);
  EXPECT_EQ(m.swap_free_bytes, 20480);
  SystemTimes a{100, 1000}, b{150, 1100};
  EXPECT_FLOAT_EQ(cpuShare(a.busy_jiffies, b.busy_jiffies, a, b), 0.5f);
  EXPECT_FLOAT_EQ(cpuShare(10, 5, a, b), 0.f);
}

TEST(ProcStats, ReadsThisProcess) {
  const auto t = readProcessTimes(getpid());
  ASSERT_TRUE(t);
  EXPECT_GT(t->rss_bytes, 0);
  EXPECT_TRUE(readSystemTimes());
  EXPECT_GT(readMemoryInfo().total_bytes, 0);
  EXPECT_FALSE(readProcessTimes(-5));
}

TEST(OutputBatcher, MergesPerCommandAndFlushesOnSizeOrAge) {
  OutputBatcher b(10, 1000);
  EXPECT_FALSE(b.due(0));
  b.add("a", "hi ", 0);
  b.add("b", "x", 100);
  b.add("a", "there", 200);
  EXPECT_FALSE(b.due(500));
  EXPECT_TRUE(b.due(1000));
  const auto batch = b.take();
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_EQ(batch[0].second, "hi there");
  EXPECT_TRUE(b.empty());
  b.add("c", "0123456789", 5000);
  EXPECT_TRUE(b.due(5000));
}

TEST(OutputLines, EndsLinesAtNewlineAndDropsAPtysCarriageReturn) {
  EXPECT_EQ(outputLines("a\r\nb\n"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(outputLines("one\ntwo"), (std::vector<std::string>{"one", "two"}));
  EXPECT_EQ(outputLines("\r\n\n"), (std::vector<std::string>{"", ""}));
  EXPECT_EQ(outputLines("mid\rline\r\n"), (std::vector<std::string>{"mid\rline"}));
  EXPECT_TRUE(outputLines("").empty());
}
